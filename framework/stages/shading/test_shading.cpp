// Shading, checked on the iso renderer's sphere: the 0.5 isosurface of the
// sphere phantom is the sphere of radius R = 0.35 N around the centre c
// (phantoms.h), so at the analytic hit point p of each ray the true normal
// is n = (p - c) / R, pointing out of the bright inside (lighting.glsl:
// n = -grad f / |grad f|), towards the viewer on the visible side. The
// colour is computed here from the documented model:
//   v = -ray direction,
//   l = the view direction turned by the light's azimuth towards the image
//       right and its elevation towards the image top:
//       l = cos(el) cos(az) (-forward) + cos(el) sin(az) right + sin(el) (-down),
//   Phong:       (ka + kd max(n.l, 0)) colour + ks max(r.v, 0)^shininess,
//                r = 2 (n.l) n - l (the reflection of -l about n);
//   Blinn-Phong: the same with max(n.h, 0), h = (l + v) / |l + v|;
//   and no highlight where n.l <= 0.
// The GPU's normal comes from central differences of the trilinear field at
// its own hit point, so it differs from the analytic normal slightly: a
// large phantom (N = 96, R = 33.6 voxels) keeps that small, and the
// tolerance below is derived from it.
// (The iso renderer's first crossing always comes from the side below the
// isovalue, so -grad f already faces the viewer there: the two-sided flip
// and the normal's sign cannot be seen through it, only both together.)
#include <gtest/gtest.h>

#include <cstring>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "support/gl_fixture.h"
#include "voxlab/phantoms.h"

namespace voxlab::testing {
namespace {

constexpr int kN = 96;
const glm::dvec3 kColour(0.7, 0.5, 0.3);
constexpr double kKa = 0.2, kKd = 0.6;

struct ShadingCase {
    const char* name;
    double azimuth, elevation;
    int blinn;
    double ks, shininess;
};

std::ostream& operator<<(std::ostream& os, const ShadingCase& c) { return os << c.name; }

double radians(double degrees) { return degrees * M_PI / 180.0; }

// The colour the documented model gives for a unit normal n, light l and
// view v.
glm::dvec3 expectedColour(const ShadingCase& c, glm::dvec3 n, glm::dvec3 l, glm::dvec3 v) {
    const double nl = glm::dot(n, l);
    double highlight = 0.0;
    if (nl > 0.0) {
        double s;
        if (c.blinn) {
            s = glm::dot(n, glm::normalize(l + v));
        } else {
            const glm::dvec3 r = 2.0 * nl * n - l;
            s = glm::dot(r, v);
        }
        highlight = std::pow(std::max(s, 0.0), c.shininess);
    }
    return (kKa + kKd * std::max(nl, 0.0)) * kColour + glm::dvec3(c.ks * highlight);
}

Scene shadedSphereScene(const char* view, const ShadingCase& c) {
    Scene scene;
    scene.renderer = "iso";
    scene.camera.view = view;
    scene.camera.projection = Projection::Orthographic;
    scene.width = scene.height = kN;
    scene.step = 1.0;
    scene.interpolation = Interpolation::Trilinear;
    scene.parameters = {{"isovalue", 0.5},      {"refinement_steps", 8},      {"shading", 1},
                        {"blinn", double(c.blinn)}, {"ka", kKa},                  {"kd", kKd},
                        {"ks", c.ks},           {"shininess", c.shininess},   {"light_azimuth", c.azimuth},
                        {"light_elevation", c.elevation},                     {"color_r", kColour.r},
                        {"color_g", kColour.g}, {"color_b", kColour.b}};
    return scene;
}

struct ShadingError {
    double maxError = 0.0;  // largest channel difference over the checked pixels
    int checked = 0;
    int unlitSide = 0;  // checked pixels with n.l <= 0
    std::string worst;
};

// Renders the sphere and compares every pixel whose ray meets the sphere at
// n.v > 0.3 (away from the silhouette, where the hit point and with it the
// normal become ill-conditioned) with the analytic colour.
ShadingError shadingError(const Volume& v, const char* view, const ShadingCase& c) {
    const Scene scene = shadedSphereScene(view, c);
    GlTest::engine().setVolume(v);
    const Image img = GlTest::engine().render(scene);
    const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
    const double az = radians(c.azimuth), el = radians(c.elevation);
    const glm::dvec3 light = std::cos(el) * std::cos(az) * -cam.forward + std::cos(el) * std::sin(az) * cam.right +
                             std::sin(el) * -cam.down;
    const glm::dvec3 centre = 0.5 * v.extent();
    const double radius = spherePhantomRadius(kN);
    ShadingError e;
    for (int py = 0; py < scene.height; ++py)
        for (int px = 0; px < scene.width; ++px) {
            glm::dvec3 o, d;
            cam.ray(px + 0.5, py + 0.5, &o, &d);
            const double b = glm::dot(centre - o, d);
            const double q2 = glm::dot(centre - o, centre - o) - b * b;  // closest approach squared
            if (q2 >= radius * radius) continue;
            const glm::dvec3 p = o + (b - std::sqrt(radius * radius - q2)) * d;
            const glm::dvec3 n = (p - centre) / radius;
            if (glm::dot(n, -d) <= 0.3) continue;
            ++e.checked;
            if (glm::dot(n, light) <= 0.0) ++e.unlitSide;
            const glm::dvec3 want = expectedColour(c, n, light, -d);
            const glm::dvec3 got(img.at(px, py));
            const glm::dvec3 diff = glm::abs(got - want);
            const double err = std::max({diff.r, diff.g, diff.b});
            if (err > e.maxError) {
                e.maxError = err;
                char buf[200];
                std::snprintf(buf, sizeof buf,
                              "pixel (%d, %d), n.l %.3f: got (%.4f, %.4f, %.4f), want (%.4f, %.4f, %.4f)", px, py,
                              glm::dot(n, light), got.r, got.g, got.b, want.r, want.g, want.b);
                e.worst = buf;
            }
        }
    return e;
}

class Shading : public GlTest, public ::testing::WithParamInterface<ShadingCase> {};

// Tolerance 0.005 per channel (measured: 2e-4). The GPU's normal deviates
// from the analytic one by the discretisation. The two samples of a central
// difference lie exactly one voxel apart, at the same place within their
// cells, so trilinear interpolation's error (periodic with the cell) almost
// cancels; what is left, and the difference quotient's own error on the
// field linear in r = |p - c|, are of order h^2 / R^2 ~ 1e-3 rad at
// R = 33.6 voxels. The hit point is within ~0.01 voxel (test_iso.cpp),
// which turns the true normal by 0.01 / R ~ 3e-4 rad. The diffuse term then
// moves by kd * 1e-3; the highlight max(r.v, 0)^s by at most
// ks * 2 * 1e-3 * max_a |d cos^s(a) / da| (r turns twice as fast as n), and
// that slope is 2.9 for s = 24: about 0.002 in all.
constexpr double kShadingTolerance = 0.005;

TEST_P(Shading, SphereMatchesTheAnalyticNormals) {
    const Volume v = makePhantom("phantom:sphere:" + std::to_string(kN));
    const ShadingCase c = GetParam();
    for (const char* view : {"+z", "-y"}) {
        SCOPED_TRACE(std::string("view ") + view);
        const ShadingError e = shadingError(v, view, c);
        std::printf("[ measured ] %s, view %s: max channel error %.4f over %d pixels (%d on the unlit side)\n",
                    c.name, view, e.maxError, e.checked, e.unlitSide);
        EXPECT_GT(e.checked, 2500);  // pi R^2 (1 - 0.09) = 3200 pixels
        EXPECT_LT(e.maxError, kShadingTolerance) << e.worst;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Lights, Shading,
    ::testing::Values(
        ShadingCase{"headlight_phong", 0, 0, 0, 0.3, 24}, ShadingCase{"headlight_blinn", 0, 0, 1, 0.3, 24},
        ShadingCase{"headlight_diffuse_only", 0, 0, 0, 0.0, 24},
        ShadingCase{"right45_phong", 45, 0, 0, 0.3, 24}, ShadingCase{"right45_blinn", 45, 0, 1, 0.3, 24},
        ShadingCase{"right45_diffuse_only", 45, 0, 1, 0.0, 24},
        ShadingCase{"above30_phong", 0, 30, 0, 0.3, 24}, ShadingCase{"above30_blinn", 0, 30, 1, 0.3, 24},
        ShadingCase{"above30_diffuse_only", 0, 30, 0, 0.0, 24},
        // Lower left and behind-ish, a broad highlight (shininess 4).
        ShadingCase{"lowerleft_phong_broad", -60, -20, 0, 0.4, 4},
        // Light from the side, Blinn with shininess 1: on the left half
        // n.l < 0 while n.h > 0, where only "no highlight where the light
        // does not reach" keeps the colour at ambient.
        ShadingCase{"side90_blinn_broad", 90, 0, 1, 0.4, 1}),
    [](const auto& info) { return std::string(info.param.name); });

// min_gradient is a fraction of the value range (here 0..1) per unit length.
// The sphere's ramp gives |grad f| = 1/W = 0.25 at the surface: a threshold
// above that (0.3, or 1: everything below it) leaves every surface pixel
// the unlit colour exactly; one below it (0.2) lights them.
TEST_F(GlTest, MinGradientLeavesTheSurfaceUnlit) {
    const Volume v = makePhantom("phantom:sphere:48");
    const double radius = spherePhantomRadius(48);
    for (double minGradient : {1.0, 0.3, 0.2}) {
        SCOPED_TRACE("min_gradient " + std::to_string(minGradient));
        Scene scene = shadedSphereScene("+z", ShadingCase{"headlight", 0, 0, 0, 0.3, 24});
        scene.width = scene.height = 48;
        scene.parameters["min_gradient"] = minGradient;
        engine().setVolume(v);
        const Image img = engine().render(scene);
        const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
        const glm::vec3 unlit(kColour);
        int hits = 0, unlitCount = 0;
        for (int py = 0; py < scene.height; ++py)
            for (int px = 0; px < scene.width; ++px) {
                glm::dvec3 o, d;
                cam.ray(px + 0.5, py + 0.5, &o, &d);
                const glm::dvec3 oc = 0.5 * v.extent() - o;
                const double closest = glm::length(oc - glm::dot(oc, d) * d);
                if (closest > 0.9 * radius) continue;
                ++hits;
                if (glm::vec3(img.at(px, py)) == unlit) ++unlitCount;
            }
        EXPECT_GT(hits, 700);
        if (minGradient > 0.25)
            EXPECT_EQ(unlitCount, hits);
        else
            EXPECT_EQ(unlitCount, 0);
    }
}

// Volume data has no inside: lighting is two-sided. A bright ball seen through
// "high values are opaque" and a dark hole (1 - f) seen through "low values
// are opaque" are the same surface, but their gradients point opposite ways;
// with the normal flipped towards the viewer both must shade alike. Without
// the flip the hole's normals face away and only the ambient term remains.
TEST_F(GlTest, LightingIsTwoSided) {
    const Volume ball = makePhantom("phantom:sphere:32");
    std::vector<float> inverted(ball.voxelCount());
    for (std::size_t i = 0; i < inverted.size(); ++i) inverted[i] = 1.0f - float(ball.valueAt(i));
    std::vector<std::uint8_t> bytes(inverted.size() * sizeof(float));
    std::memcpy(bytes.data(), inverted.data(), bytes.size());
    const Volume hole(ball.dims(), VoxelType::Float32, ball.spacing(), bytes, "hole");

    Scene scene;
    scene.renderer = "composite";
    scene.camera.azimuth = 30, scene.camera.elevation = 20;
    scene.width = scene.height = 48;
    scene.parameters = {{"shading", 1}};
    const glm::vec3 white(1.0f);
    // Opaque above 0.5 for the ball, below 0.5 for the hole: mirror images.
    scene.transferFunction = TransferFunction({{0.45, white, 0.0f}, {0.55, white, 1.0f}});
    engine().setVolume(ball);
    const Image lit = engine().render(scene);
    scene.transferFunction = TransferFunction({{0.45, white, 1.0f}, {0.55, white, 0.0f}});
    engine().setVolume(hole);
    const Image mirrored = engine().render(scene);

    // Float rounding of 1 - f only: both see the same surface.
    float worst = 0.0f, brightest = 0.0f;
    for (std::size_t i = 0; i < lit.rgba.size(); ++i) {
        worst = std::max(worst, std::abs(lit.rgba[i] - mirrored.rgba[i]));
        brightest = std::max(brightest, mirrored.rgba[i]);
    }
    EXPECT_LT(worst, 2e-3f);
    EXPECT_GT(brightest, 0.8f) << "the hole is lit by its ambient term only: normals face away";
}

}  // namespace
}  // namespace voxlab::testing
