// Pre-integrated classification (the preintegration stage, composite with
// `preintegrated` on), against the analytic integral and against fine
// post-classification on real data.
//
// Oracle 1, the table: one sample per ray makes the pixel one segment. A
// 32^3 float volume of unit spacing holds, in blocks of 8 x 8 columns, linear
// ramps along z, v = base + slope k (k the voxel layer, centres at k + 1/2).
// An orthographic +z view with step 32 takes one sample per ray, at z = 16;
// its segment reaches to z = 48, beyond the box, where the hardware filter
// clamps to the last layer. So the segment runs linearly from sf = v(z=16) =
// base + 15.5 slope to sb = base + 31 slope over L = 32 unit lengths, and the
// pixel (over black) is its colour C and opacity A. Two voxels pin the value
// range to [0, 255], so every (sf, sb) here is an integer and falls on a
// table texel (texel i is the value i): the lookup adds no interpolation.
//
// With opacity per unit length linear in the value, alpha(s) = a0 + b s,
// the extinction tau = -ln(1 - alpha) has a closed-form integral:
//     int tau ds = [(u ln u - u) / b],   u = 1 - a0 - b s,
// so A = 1 - exp(-L / (sb - sf) int_sf^sb tau ds) (and tau(sf) L when sf = sb),
// and with a constant colour c, C = c A. With a colour that changes along
// the value, C = int c(s(t)) tau(s(t)) T(t) dt is integrated in double with
// 200000 midpoint steps of T(t) = exp(-int_0^t tau): a different
// discretisation from the shader's compositing of sub-segments.
//
// Tolerance: 1.5 grey levels. Half a level is the 8-bit rounding; the
// stage's midpoint rule with one sub-segment per table texel (30 to 125 here)
// errs by about (width^2 / 24) |tau''| per piece, under 1e-4 in opacity; the
// float compositing of 125 pieces adds about 1e-5. A missing opacity
// correction, a swapped order or an unpremultiplied colour moves pixels by
// 10 levels or more.
//
// Oracle 2, real data: at step 4, on the bonsai and the tooth with thin
// peaks in their transfer functions, the pre-integrated image is at least 2x
// closer (mean absolute difference over RGB) to post-classification at step
// 0.25 than post-classification at step 4 is (the criterion).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

#include "support/gl_fixture.h"
#include "voxlab/camera.h"
#include "voxlab/stage_registry.h"

namespace voxlab::testing {
namespace {

constexpr int kSize = 32;
constexpr int kImage = 64;
const int kSlopes[4] = {-4, -2, 2, 4};
const int kOffsets[4] = {-40, -10, 10, 40};

// The segment of block (bx, by): front and back values.
glm::dvec2 blockSegment(int bx, int by) {
    const double front = 128.0 + kOffsets[by];
    return {front, front + 15.5 * kSlopes[bx]};
}

Volume blockRamps() {
    std::vector<float> values(std::size_t(kSize) * kSize * kSize);
    std::size_t idx = 0;
    for (int k = 0; k < kSize; ++k)
        for (int j = 0; j < kSize; ++j)
            for (int i = 0; i < kSize; ++i) {
                const double base = blockSegment(i / 8, j / 8).x - 15.5 * kSlopes[i / 8];
                values[idx++] = float(base + kSlopes[i / 8] * k);
            }
    values.front() = 0.0f;  // the value range: [0, 255]
    values.back() = 255.0f;
    std::vector<std::uint8_t> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return Volume(glm::ivec3(kSize), VoxelType::Float32, glm::dvec3(1.0), bytes, "block ramps");
}

Scene segmentScene(const TransferFunction& tf) {
    Scene scene;
    scene.renderer = "composite";
    scene.camera.view = "+z";
    scene.camera.projection = Projection::Orthographic;
    scene.width = scene.height = kImage;
    scene.step = kSize;  // one sample per ray
    scene.interpolation = Interpolation::Hardware;
    scene.transferFunction = tf;
    scene.parameters["preintegrated"] = 1.0;
    scene.parameters["early_termination"] = 1.0;
    return scene;
}

// Extinction integral of alpha(s) = a0 + b s from s0 to s1 (b != 0).
double tauIntegral(double a0, double b, double s0, double s1) {
    auto antiderivative = [&](double s) {
        const double u = 1.0 - a0 - b * s;
        return (u * std::log(u) - u) / b;
    };
    return antiderivative(s1) - antiderivative(s0);
}

// C and A of the segment by fine quadrature in double: alpha and colour as
// functions of the value.
glm::dvec4 quadrature(const std::function<double(double)>& alpha, const std::function<glm::dvec3(double)>& colour,
                      double sf, double sb, double length) {
    constexpr int kSteps = 200000;
    const double dt = length / kSteps;
    double optical = 0.0;  // int_0^t tau
    glm::dvec3 c(0.0);
    for (int n = 0; n < kSteps; ++n) {
        const double s = sf + (sb - sf) * (n + 0.5) / kSteps;
        const double tau = -std::log(1.0 - alpha(s));
        c += colour(s) * tau * std::exp(-(optical + 0.5 * tau * dt)) * dt;
        optical += tau * dt;
    }
    return {c, 1.0 - std::exp(-optical)};
}

struct Pixel {
    int bx, by;
    glm::dvec4 rgba;
};

// The pixels at least 1.5 voxels inside a block, with their block.
std::vector<Pixel> blockPixels(const Image& image, const Scene& scene) {
    const Camera cam = Camera::make(scene.camera, glm::dvec3(kSize), kImage, kImage);
    std::vector<Pixel> pixels;
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) {
            glm::dvec3 origin, direction;
            cam.ray(x + 0.5, y + 0.5, &origin, &direction);
            const glm::dvec2 w(origin.x, origin.y);
            if (w.x < 0.0 || w.y < 0.0 || w.x >= kSize || w.y >= kSize) continue;
            const glm::dvec2 inBlock = glm::mod(w, 8.0);
            if (glm::any(glm::lessThan(inBlock, glm::dvec2(1.5))) || glm::any(glm::greaterThan(inBlock, glm::dvec2(6.5))))
                continue;
            const glm::vec4 p = image.at(x, y);
            pixels.push_back({int(w.x / 8), int(w.y / 8), glm::dvec4(p)});
        }
    return pixels;
}

class Preintegration : public GlTest {};

TEST_F(Preintegration, TableEntriesEqualTheAnalyticIntegralForAnOpacityLinearInTheValue) {
    const Volume volume = blockRamps();
    engine().setVolume(volume);
    // alpha from 0.001 at 0 to 0.04 at 255, white.
    const double a0 = 0.001, b = (0.04 - 0.001) / 255.0;
    const TransferFunction tf({{0.0, glm::vec3(1.0f), float(a0)}, {255.0, glm::vec3(1.0f), float(a0 + 255.0 * b)}});
    const Scene scene = segmentScene(tf);
    const std::vector<Pixel> pixels = blockPixels(engine().render(scene), scene);
    ASSERT_GT(pixels.size(), 16u * 4u) << "too few pixels inside the blocks";
    int checked[4][4] = {};
    for (const Pixel& p : pixels) {
        const glm::dvec2 seg = blockSegment(p.bx, p.by);
        const double optical = double(kSize) / (seg.y - seg.x) * tauIntegral(a0, b, seg.x, seg.y);
        const double opacity = 1.0 - std::exp(-optical);
        SCOPED_TRACE("segment " + std::to_string(seg.x) + " -> " + std::to_string(seg.y));
        EXPECT_NEAR(255.0 * p.rgba.r, 255.0 * opacity, 1.5) << "white over black: the red channel is C = A";
        EXPECT_NEAR(255.0 * p.rgba.g, 255.0 * opacity, 1.5);
        ++checked[p.bx][p.by];
    }
    for (int bx = 0; bx < 4; ++bx)
        for (int by = 0; by < 4; ++by) EXPECT_GT(checked[bx][by], 0) << "block " << bx << "," << by;
}

TEST_F(Preintegration, TableEntriesEqualTheIntegralWhenTheColourChangesAlongTheSegment) {
    const Volume volume = blockRamps();
    engine().setVolume(volume);
    // Red at low values, blue at high ones; opacity linear, 0.01 to 0.08.
    const double a0 = 0.01, b = 0.07 / 255.0;
    const TransferFunction tf({{0.0, glm::vec3(1.0f, 0.0f, 0.0f), float(a0)}, {255.0, glm::vec3(0.0f, 0.0f, 1.0f), 0.08f}});
    const Scene scene = segmentScene(tf);
    const std::vector<Pixel> pixels = blockPixels(engine().render(scene), scene);
    ASSERT_GT(pixels.size(), 16u * 4u);
    glm::dvec4 integral[4][4];
    for (int bx = 0; bx < 4; ++bx)
        for (int by = 0; by < 4; ++by) {
            const glm::dvec2 seg = blockSegment(bx, by);
            integral[bx][by] = quadrature([&](double s) { return a0 + b * s; },
                                          [](double s) { return glm::dvec3(1.0 - s / 255.0, 0.0, s / 255.0); },
                                          seg.x, seg.y, double(kSize));
        }
    for (const Pixel& p : pixels) {
        const glm::dvec2 seg = blockSegment(p.bx, p.by);
        const glm::dvec4& expected = integral[p.bx][p.by];
        SCOPED_TRACE("segment " + std::to_string(seg.x) + " -> " + std::to_string(seg.y));
        EXPECT_NEAR(255.0 * p.rgba.r, 255.0 * expected.r, 1.5) << "red: the front's colour, seen first";
        EXPECT_NEAR(255.0 * p.rgba.b, 255.0 * expected.b, 1.5) << "blue";
    }
}

// Mean absolute difference over RGB, in grey levels.
double meanDifference(const Image& a, const Image& b) {
    double sum = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) sum += std::abs(toByte(a.at(x, y)[c]) - toByte(b.at(x, y)[c]));
    return sum / (3.0 * a.width * a.height);
}

// One of the stage's grading scenes.
Scene stageScene(const std::string& file) {
    return Scene::load(std::string(VOXLAB_SOURCE_DIR) + "/reference/preintegration/scenes/" + file);
}

struct Closeness {
    double post, preintegrated;
};

Closeness closenessAtStep4(const std::string& sceneFile) {
    Scene scene = stageScene(sceneFile);
    const Volume volume = loadVolume(scene.dataset);
    GlTest::engine().setVolume(volume);
    scene.step = 0.25;
    scene.parameters["preintegrated"] = 0.0;
    const Image fine = GlTest::engine().render(scene);
    scene.step = 4.0;
    const Image post = GlTest::engine().render(scene);
    scene.parameters["preintegrated"] = 1.0;
    const Image preintegrated = GlTest::engine().render(scene);
    return {meanDifference(post, fine), meanDifference(preintegrated, fine)};
}

TEST_F(Preintegration, AtStep4ItIsTwiceAsCloseToStepQuarterAsPostClassificationOnTheBonsai) {
    const Closeness c = closenessAtStep4("bonsai_thin_peaks.json");
    std::printf("bonsai, step 4 vs post-classification at step 0.25: post %.3f, pre-integrated %.3f grey levels (%.2fx)\n",
                c.post, c.preintegrated, c.post / c.preintegrated);
    EXPECT_GE(c.post, 2.0 * c.preintegrated);
}

TEST_F(Preintegration, AtStep4ItIsTwiceAsCloseToStepQuarterAsPostClassificationOnTheTooth) {
    const Closeness c = closenessAtStep4("tooth_shell.json");
    std::printf("tooth, step 4 vs post-classification at step 0.25: post %.3f, pre-integrated %.3f grey "
                "levels (%.2fx)\n",
                c.post, c.preintegrated, c.post / c.preintegrated);
    EXPECT_GE(c.post, 2.0 * c.preintegrated);
}

// Early termination stops a ray after the segment that takes its opacity to
// the threshold: the image differs from the full one only where opacity is
// near 1, and by at most the light those remaining segments would add
// (1 - threshold of it).
TEST_F(Preintegration, ComposesWithEarlyTermination) {
    Scene scene = stageScene("bonsai_thin_peaks.json");
    const Volume volume = loadVolume(scene.dataset);
    engine().setVolume(volume);
    scene.parameters["early_termination"] = 1.0;
    const Image full = engine().render(scene);
    scene.parameters["early_termination"] = 0.9;
    const Image early = engine().render(scene);
    double largest = 0.0;
    for (int y = 0; y < full.height; ++y)
        for (int x = 0; x < full.width; ++x)
            for (int c = 0; c < 3; ++c)
                largest = std::max(largest, double(std::abs(full.at(x, y)[c] - early.at(x, y)[c])));
    EXPECT_LE(largest, 0.1 + 1e-4) << "early termination changed a pixel by more than what lies behind 0.9 opacity";
    EXPECT_GT(largest, 0.0) << "early termination had no effect: is it still applied?";
}

// Shading multiplies the segment's colour by the lighting: with ka = 1,
// kd = ks = 0 the lighting is 1 everywhere and the image is the unshaded one.
TEST_F(Preintegration, ComposesWithShading) {
    Scene scene = stageScene("tooth_shell.json");
    const Volume volume = loadVolume(scene.dataset);
    engine().setVolume(volume);
    scene.parameters["shading"] = 0.0;
    const Image plain = engine().render(scene);
    scene.parameters["shading"] = 1.0;
    scene.parameters["ka"] = 1.0, scene.parameters["kd"] = 0.0, scene.parameters["ks"] = 0.0;
    EXPECT_LE(meanDifference(engine().render(scene), plain), 0.01) << "ambient-only shading changed the image";
    scene.parameters["ka"] = 0.2, scene.parameters["kd"] = 0.7, scene.parameters["ks"] = 0.3;
    EXPECT_GT(meanDifference(engine().render(scene), plain), 2.0) << "shading did not change the image";
}

// The table is made again when the transfer function or the step changes:
// an engine that rendered something else first gives the same image as a
// fresh one.
TEST_F(Preintegration, TheTableFollowsTheTransferFunctionAndTheStep) {
    Scene scene = stageScene("bonsai_thin_peaks.json");
    const Volume volume = loadVolume(scene.dataset);
    Scene other = scene;
    other.step = 2.0;
    other.transferFunction = TransferFunction({{0.0, glm::vec3(1.0f), 0.0f}, {255.0, glm::vec3(1.0f), 0.3f}});
    engine().setVolume(volume);
    const Image first = engine().render(scene);
    engine().render(other);
    EXPECT_EQ(meanDifference(engine().render(scene), first), 0.0);
    RenderEngine fresh(rendererRegistry());
    fresh.setVolume(volume);
    EXPECT_EQ(meanDifference(fresh.render(other), engine().render(other)), 0.0);
}

}  // namespace
}  // namespace voxlab::testing
