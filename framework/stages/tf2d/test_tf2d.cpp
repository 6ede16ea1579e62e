// The "tf2d" renderer (compositing classified by the 2D transfer function
// over value and gradient magnitude) against CPU math written here:
//  - Levoy's triangle, evaluated here from its formula, read back through a
//    float field whose value and gradient are known at every voxel centre:
//    f = s * x (x the voxel-centre coordinate), |grad f| = s per unit length
//    (central differences, one-sided at the faces, are exact on it);
//  - layers combine as 1 - prod(1 - alpha_i), colour the alpha-weighted mean;
//  - a box widget is a constant opacity over a value and gradient range;
//  - a box over the whole domain is a constant 1D transfer function, so the
//    image equals the composite renderer's.
// Shading (on by default for tf2d) is switched off: colours stay the
// widgets' own.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "support/axis_columns.h"
#include "support/error_of.h"
#include "support/gl_fixture.h"

namespace voxlab::testing {
namespace {

// ---------------------------------------------------------------------------
// Oracle: the widgets' formulas, written for the test.

struct Triangle {
    double value, radius, alpha;
    glm::dvec3 colour{1.0};
};

// Levoy (1988): full opacity av on the isovalue, falling linearly to 0 at a
// value distance of r * g (the surface stays r unit lengths thick whatever
// the gradient); where g = 0 only f == fv itself is opaque.
double levoy(const Triangle& t, double f, double g) {
    const double d = std::abs(f - t.value);
    if (g == 0.0) return d == 0.0 ? t.alpha : 0.0;
    return d <= t.radius * g ? t.alpha * (1.0 - d / (t.radius * g)) : 0.0;
}

Tf2dWidget triangleWidget(const Triangle& t) {
    Tf2dWidget w;
    w.kind = Tf2dWidget::Kind::Triangle;
    w.valueRange = glm::dvec2(t.value);
    w.radius = t.radius;
    w.alpha = float(t.alpha);
    w.color = glm::vec3(t.colour);
    return w;
}

Tf2dWidget boxWidget(glm::dvec2 values, glm::dvec2 gradients, double alpha, glm::vec3 colour = glm::vec3(1.0f)) {
    Tf2dWidget w;
    w.kind = Tf2dWidget::Kind::Box;
    w.valueRange = values;
    w.gradientRange = gradients;
    w.alpha = float(alpha);
    w.color = colour;
    return w;
}

// The linear field f = s * (i + 1/2) over `width` columns along x, `depth`
// voxels along z (the view axis), spacing h on every axis. The value grows
// by s per voxel, s / h per world unit; per unit length (the smallest
// spacing, h) that is |grad f| = s, whatever h.
Volume linearField(int width, int depth, double s, double h = 1.0) {
    const glm::ivec3 d(width, 3, depth);
    std::vector<std::uint8_t> bytes(std::size_t(d.x) * d.y * d.z * 4);
    std::size_t idx = 0;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i, ++idx) {
                const float v = float(s * (i + 0.5));
                std::memcpy(&bytes[idx * 4], &v, 4);
            }
    return Volume(d, VoxelType::Float32, glm::dvec3(h), bytes, "linear");
}

// The +z axis view of such a field: nearest, step 1, one pixel per column,
// white widgets over black, no shading, no early termination. Pixel (i, *)
// then composites `depth` samples of the classification at f = s (i + 1/2),
// g = s.
Scene fieldScene(const Volume& v, const std::vector<Tf2dWidget>& widgets) {
    Scene scene = axisViewScene(v, kAxisViews[0], "tf2d");
    scene.transferFunction2D = TransferFunction2D(widgets);
    scene.parameters["shading"] = 0.0;
    scene.parameters["early_termination"] = 1.0;
    return scene;
}

// What one render over black and one over white tell about a pixel: its
// total opacity A (white - black = 1 - A) and its premultiplied colour C
// (the render over black).
struct Readout {
    double opacity;
    glm::dvec3 colour;  // premultiplied
};

std::vector<Readout> readColumns(const Volume& v, Scene scene) {
    GlTest::engine().setVolume(v);
    scene.background = glm::vec3(0.0f);
    const Image black = GlTest::engine().render(scene);
    scene.background = glm::vec3(1.0f);
    const Image white = GlTest::engine().render(scene);
    std::vector<Readout> out;
    for (int i = 0; i < v.dims().x; ++i) {
        const glm::vec4 b = black.at(i, 1), w = white.at(i, 1);
        out.push_back({1.0 - (w.g - b.g), glm::dvec3(b)});
    }
    return out;
}

// The per-unit-length opacity of one sample, recovered from a column of n
// identical samples at step 1: A = 1 - (1 - alpha)^n.
double perSampleAlpha(double columnOpacity, int n) {
    return 1.0 - std::pow(std::max(1.0 - columnOpacity, 0.0), 1.0 / n);
}

// Tolerance for alpha recovered from the float image: the image is float
// (no 8-bit rounding), so only float arithmetic separates GPU and CPU,
// ~1e-6 in A; recovering alpha magnifies that by
// dalpha/dA = (1 - A)^(1/n - 1) / n, at most ~10 for the opacities used here.
constexpr double kAlphaTolerance = 1e-4;

// ---------------------------------------------------------------------------

// A box over the whole domain (every value, gradients 0..1e30) with one
// colour and opacity classifies every sample alike, as a constant 1D
// transfer function does: tf2d and composite must then draw the same image
// (same scene: perspective orbit, trilinear, step 0.5, coloured
// background). Tolerance 1/255; only float rounding separates them (the 1D
// table of a constant function is exact).
TEST_F(GlTest, BoxOverTheWholeDomainEqualsCompositeWithAConstantTransferFunction) {
    const Volume v = loadVolume(datasetPath("fuel.nrrd"));
    const glm::vec3 colour(0.9f, 0.55f, 0.25f);
    const float alpha = 0.04f;
    Scene scene;
    scene.camera.azimuth = -50.0, scene.camera.elevation = 15.0;
    scene.width = scene.height = 80;
    scene.step = 0.5;
    scene.interpolation = Interpolation::Trilinear;
    scene.background = glm::vec3(0.1f, 0.2f, 0.3f);
    scene.parameters["shading"] = 0.0;

    scene.renderer = "composite";
    scene.transferFunction = TransferFunction({{0.0, colour, alpha}});
    engine().setVolume(v);
    const Image composite = engine().render(scene);

    scene.renderer = "tf2d";
    scene.transferFunction.reset();
    scene.transferFunction2D = TransferFunction2D(
        {boxWidget({v.minValue() - 1.0, v.maxValue() + 1.0}, {0.0, 1e30}, alpha, colour)});
    const Image tf2d = engine().render(scene);

    double worst = 0.0, covered = 0.0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x)
            for (int ch = 0; ch < 3; ++ch) {
                worst = std::max(worst, double(std::abs(composite.at(x, y)[ch] - tf2d.at(x, y)[ch])));
                covered += std::abs(composite.at(x, y)[ch] - scene.background[ch]);
            }
    EXPECT_LE(worst, 1.0 / 255.0);
    EXPECT_GT(covered / (3.0 * scene.width * scene.height), 0.05);  // the volume shows
}

// Levoy's formula at known (f, g): a triangle at fv = 20.6 with radius 2.5
// over f = 2 (i + 1/2), g = 2: r g = 5, so the columns f = 17, 19, 21, 23,
// 25 lie inside at distances 3.6, 1.6, 0.4, 2.4, 4.4 and the others
// outside. Each pixel column composites 4 identical samples; alpha is
// recovered from the column's opacity and compared with levoy(). The same
// on a grid of spacing 0.5 (gradients are per unit length = the smallest
// spacing, so still s per unit), and with other slopes, radii and opacities
// (a steep field and a shallow one whose triangle covers all but two
// columns).
TEST_F(GlTest, TriangleFollowsLevoysFormula) {
    struct Case {
        double spacing, s;
        Triangle t;
    };
    for (const Case& c : {Case{1.0, 2.0, {20.6, 2.5, 0.7}}, Case{0.5, 2.0, {20.6, 2.5, 0.7}},
                          Case{1.0, 3.0, {30.0, 4.0, 0.45}}, Case{1.0, 0.5, {5.3, 9.0, 0.9}}}) {
        SCOPED_TRACE("spacing " + std::to_string(c.spacing) + ", s " + std::to_string(c.s) + ", fv " +
                     std::to_string(c.t.value));
        const int width = 16, depth = 4;
        const Volume v = linearField(width, depth, c.s, c.spacing);
        const std::vector<Readout> got = readColumns(v, fieldScene(v, {triangleWidget(c.t)}));
        int inside = 0, outside = 0;
        for (int i = 0; i < width; ++i) {
            const double f = c.s * (i + 0.5);
            const double want = levoy(c.t, f, c.s);
            (want > 0.0 ? inside : outside)++;
            EXPECT_NEAR(perSampleAlpha(got[i].opacity, depth), want, kAlphaTolerance) << "column " << i << " f = " << f;
            // White widget: the premultiplied colour is the opacity.
            EXPECT_NEAR(got[i].colour.r, got[i].opacity, 1e-5) << "column " << i;
        }
        // Every case has columns on both sides of the triangle's edges.
        EXPECT_GE(inside, 4);
        EXPECT_GE(outside, 1);
    }
}

// Where the gradient is 0 (a constant field) the triangle is a line: only
// the value fv itself gets the widget's opacity. A constant volume of value
// 0 with a triangle at 0 shows 1 - (1 - av)^n; one at 0.25 or -1 (radius 3)
// shows nothing.
TEST_F(GlTest, TriangleOnAFlatFieldIsOpaqueOnlyAtItsValue) {
    const Volume v = linearField(6, 5, 0.0);  // every voxel 0
    for (double fv : {0.0, 0.25, -1.0}) {
        const Triangle t{fv, 3.0, 0.35};
        const std::vector<Readout> got = readColumns(v, fieldScene(v, {triangleWidget(t)}));
        const double want = fv == 0.0 ? 0.35 : 0.0;
        for (int i = 0; i < 6; ++i)
            EXPECT_NEAR(perSampleAlpha(got[i].opacity, 5), want, kAlphaTolerance) << "fv " << fv << " column " << i;
    }
}

// Two overlapping triangles of different colours: the sample's opacity is
// 1 - (1 - a1)(1 - a2) and its colour the alpha-weighted mean
// (a1 c1 + a2 c2) / (a1 + a2). With n identical samples the pixel's
// premultiplied colour is that colour times the column's opacity.
// Tolerances: alpha as above; colour 1e-4 (divided by opacities >= 0.02).
TEST_F(GlTest, TwoWidgetsCombineAsIndependentLayers) {
    const double s = 2.0;
    const int width = 16, depth = 3;
    const Volume v = linearField(width, depth, s);
    const Triangle t1{12.0, 3.0, 0.5, {1.0, 0.2, 0.0}};
    const Triangle t2{17.5, 2.0, 0.6, {0.0, 0.4, 1.0}};
    const std::vector<Readout> got = readColumns(v, fieldScene(v, {triangleWidget(t1), triangleWidget(t2)}));
    int both = 0;
    for (int i = 0; i < width; ++i) {
        SCOPED_TRACE("column " + std::to_string(i));
        const double f = s * (i + 0.5);
        const double a1 = levoy(t1, f, s), a2 = levoy(t2, f, s);
        both += a1 > 0.0 && a2 > 0.0;
        const double alpha = 1.0 - (1.0 - a1) * (1.0 - a2);
        EXPECT_NEAR(perSampleAlpha(got[i].opacity, depth), alpha, kAlphaTolerance);
        if (got[i].opacity > 0.02) {
            const glm::dvec3 colour = (a1 * t1.colour + a2 * t2.colour) / (a1 + a2);
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[i].colour[ch] / got[i].opacity, colour[ch], 1e-4);
        }
    }
    EXPECT_GE(both, 2);  // columns where the layers overlap
}

// A box is constant opacity over [v0, v1] x [g0, g1], bounds included. On
// the field f = 2 (i + 1/2), g = 2 (computed exactly: small integers in
// float):
//  - a gradient range that excludes 2 renders nothing, whatever the values;
//  - one that includes it (even [2, 2]) gives av exactly in the columns
//    whose value is in [v0, v1] (here [9, 19]: f = 9 .. 19 included, f = 7
//    and 21 not) and 0 elsewhere.
TEST_F(GlTest, BoxSelectsByValueAndGradientRange) {
    const double s = 2.0, av = 0.3;
    const int width = 16, depth = 4;
    const Volume v = linearField(width, depth, s);
    struct Case {
        glm::dvec2 values, gradients;
        bool gradientInside;
    };
    for (const Case& c : {Case{{-100, 100}, {2.5, 10}, false}, Case{{-100, 100}, {0, 1.5}, false},
                          Case{{9, 19}, {0, 1e30}, true}, Case{{9, 19}, {2, 2}, true},
                          Case{{9, 19}, {1.5, 2.5}, true}}) {
        SCOPED_TRACE("box values " + std::to_string(c.values.x) + ".." + std::to_string(c.values.y) + " gradients " +
                     std::to_string(c.gradients.x) + ".." + std::to_string(c.gradients.y));
        const std::vector<Readout> got = readColumns(v, fieldScene(v, {boxWidget(c.values, c.gradients, av)}));
        for (int i = 0; i < width; ++i) {
            const double f = s * (i + 0.5);
            const bool in = c.gradientInside && f >= c.values.x && f <= c.values.y;
            EXPECT_NEAR(perSampleAlpha(got[i].opacity, depth), in ? av : 0.0, kAlphaTolerance)
                << "column " << i << " f = " << f;
        }
    }
}

// Without a 2D transfer function tf2d uses its fallback (render_engine.h):
// one white triangle at the middle of the window, radius 1.5, opacity 0.6.
// On f = 2 (i + 1/2), g = 2 (r g = 3): with the default window (the data
// range 1..31, middle 16) the columns f = 15 and 17 get 0.6 (1 - 1/3) =
// 0.4 and every other column 0; with the window [0, 40] (middle 20) the
// columns f = 19 and 21 do. Tolerance as above.
TEST_F(GlTest, NoTwoDimensionalTransferFunctionUsesTheFallbackTriangle) {
    const double s = 2.0;
    const int width = 16, depth = 4;
    const Volume v = linearField(width, depth, s);
    for (std::optional<glm::dvec2> window : {std::optional<glm::dvec2>(), std::optional(glm::dvec2(0.0, 40.0))}) {
        Scene scene = fieldScene(v, {});
        scene.transferFunction2D.reset();
        scene.window = window;
        const std::vector<Readout> got = readColumns(v, scene);
        const double middle = window ? 20.0 : 16.0;
        const Triangle fallback{middle, 1.5, 0.6};
        for (int i = 0; i < width; ++i) {
            const double f = s * (i + 0.5), want = levoy(fallback, f, s);
            EXPECT_NEAR(want, std::abs(f - middle) == 1.0 ? 0.4 : 0.0, 1e-12);  // the oracle, restated
            EXPECT_NEAR(perSampleAlpha(got[i].opacity, depth), want, kAlphaTolerance)
                << "window middle " << middle << ", column " << i << " f = " << f;
        }
    }
}

// ---------------------------------------------------------------------------
// The scene file's "tf2d" section.

nlohmann::json sceneJson(const nlohmann::json& tf2d) {
    return {{"dataset", "phantom:sphere:16"}, {"renderer", "tf2d"}, {"tf2d", tf2d}};
}

// A scene with a "tf2d" section parses into those widgets, and renders as
// the same widgets built in code do.
TEST_F(GlTest, SceneTf2dSectionParsesAndRendersLikeTheWidgetsItDescribes) {
    const nlohmann::json tf2d = nlohmann::json::parse(R"({"widgets": [
        {"type": "triangle", "value": 20.6, "radius": 2.5, "alpha": 0.7, "color": [1, 0.5, 0]},
        {"type": "box", "value": [9, 19], "gradient": [1, 3], "alpha": 0.2, "color": [0, 0.25, 1]}]})");
    const Scene parsed = Scene::fromJson(sceneJson(tf2d), "scene.json", "");
    ASSERT_TRUE(parsed.transferFunction2D.has_value());
    const std::vector<Tf2dWidget>& w = parsed.transferFunction2D->widgets();
    ASSERT_EQ(w.size(), 2u);
    EXPECT_EQ(w[0].kind, Tf2dWidget::Kind::Triangle);
    EXPECT_DOUBLE_EQ(w[0].valueRange.x, 20.6);
    EXPECT_DOUBLE_EQ(w[0].radius, 2.5);
    EXPECT_FLOAT_EQ(w[0].alpha, 0.7f);
    EXPECT_EQ(w[0].color, glm::vec3(1.0f, 0.5f, 0.0f));
    EXPECT_EQ(w[1].kind, Tf2dWidget::Kind::Box);
    EXPECT_EQ(w[1].valueRange, glm::dvec2(9, 19));
    EXPECT_EQ(w[1].gradientRange, glm::dvec2(1, 3));
    EXPECT_FLOAT_EQ(w[1].alpha, 0.2f);

    const Volume v = linearField(16, 4, 2.0);
    Triangle t{20.6, 2.5, 0.7, {1.0, 0.5, 0.0}};
    const std::vector<Readout> built =
        readColumns(v, fieldScene(v, {triangleWidget(t), boxWidget({9, 19}, {1, 3}, 0.2, {0.0f, 0.25f, 1.0f})}));
    Scene fromFile = fieldScene(v, {});
    fromFile.transferFunction2D = parsed.transferFunction2D;
    const std::vector<Readout> read = readColumns(v, fromFile);
    double shown = 0.0;
    for (int i = 0; i < 16; ++i) {
        EXPECT_NEAR(read[i].opacity, built[i].opacity, 1e-6);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(read[i].colour[ch], built[i].colour[ch], 1e-6);
        shown += read[i].opacity;
    }
    EXPECT_GT(shown, 1.0);
}

// Errors name the scene file, the widget and the key.
TEST(Tf2dSceneJson, ErrorsNameTheWidgetAndTheKey) {
    const auto error = [](const char* text) {
        return errorOf([&] { Scene::fromJson(sceneJson(nlohmann::json::parse(text)), "scene.json", ""); });
    };
    EXPECT_NE(error(R"({"widgets": [{"type": "triangle", "value": 1, "radius": 0, "alpha": 1, "color": [1, 1, 1]}]})")
                  .find("scene.json: tf2d.widgets[0].radius"),
              std::string::npos);
    EXPECT_NE(error(R"({"widgets": [{"type": "box", "value": [0, 1], "gradient": [0, 1], "alpha": 1,
                                      "color": [1, 1, 1]},
                                     {"type": "triangle", "value": 1, "radius": 2, "alpha": 1.5,
                                      "color": [1, 1, 1]}]})")
                  .find("tf2d.widgets[1].alpha"),
              std::string::npos);
    EXPECT_NE(error(R"({"widgets": [{"type": "box", "value": [0, 1], "gradient": [-1, 1], "alpha": 1,
                                      "color": [1, 1, 1]}]})")
                  .find("tf2d.widgets[0].gradient"),
              std::string::npos);
    // An unknown widget type is rejected, naming the type.
    const std::string unknown =
        error(R"({"widgets": [{"type": "ellipse", "value": 1, "radius": 2, "alpha": 1, "color": [1, 1, 1]}]})");
    EXPECT_NE(unknown.find("tf2d.widgets[0].type"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("ellipse"), std::string::npos) << unknown;
    // A well-formed section parses without error.
    EXPECT_EQ(error(R"({"widgets": [{"type": "triangle", "value": 1, "radius": 2, "alpha": 1, "color": [1, 1, 1]}]})"),
              "");
}

}  // namespace
}  // namespace voxlab::testing
