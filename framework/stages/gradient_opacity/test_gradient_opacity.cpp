// Gradient-magnitude opacity modulation (the gradient_opacity stage, used by
// composite with `gradient_opacity` on), against an analytic field.
//
// The oracle: f(i, j, k) = 4 i + 2 on a 32^3 grid of unit spacing, a linear
// ramp along x, so |grad f| = 4 data units per unit length everywhere away
// from the two x faces (central differences are exact on a linear field;
// next to a face the sampling clamps). Seen along z, orthographic, every ray
// stays at one x: its samples all have g = 4. With a transfer function of
// constant white colour and opacity alpha per unit length, a ray through the
// whole depth D = 32 has opacity 1 - (1 - alpha w)^D, with w the ramp's
// weight at g = 4 (the opacity-corrected samples, 1 - (1 - alpha w)^step
// each, multiply to that for any step that divides D). The pixel is that
// opacity (white over black).
//
// Tolerance: 1.5 grey levels. The image is 8-bit (half a level of rounding)
// and 64 samples each round their opacity in float (~1e-7 each): the rest is
// margin. A wrong weight moves the pixel by far more: w = 0.5 against 1 is
// 63 levels, 0.25 against 0.5 is 33.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/gl_fixture.h"

namespace voxlab::testing {
namespace {

constexpr double kAlpha = 0.05;  // opacity per unit length
constexpr int kDepth = 32;

Volume linearRamp() {
    std::vector<std::uint8_t> bytes(std::size_t(kDepth) * kDepth * kDepth);
    std::size_t idx = 0;
    for (int k = 0; k < kDepth; ++k)
        for (int j = 0; j < kDepth; ++j)
            for (int i = 0; i < kDepth; ++i) bytes[idx++] = std::uint8_t(4 * i + 2);
    return Volume(glm::ivec3(kDepth), VoxelType::UInt8, glm::dvec3(1.0), bytes, "ramp");
}

Scene rampScene() {
    Scene scene;
    scene.renderer = "composite";
    scene.camera.view = "+z";
    scene.camera.projection = Projection::Orthographic;
    scene.width = scene.height = 64;
    scene.step = 0.5;
    scene.interpolation = Interpolation::Trilinear;
    scene.transferFunction = TransferFunction({{0.0, glm::vec3(1.0f), float(kAlpha)}, {255.0, glm::vec3(1.0f), float(kAlpha)}});
    scene.parameters["early_termination"] = 1.0;
    return scene;
}

double rayOpacity(double weight) { return 1.0 - std::pow(1.0 - kAlpha * weight, kDepth); }

class GradientOpacity : public GlTest {};

TEST_F(GradientOpacity, TheWeightOfALinearRampMatchesTheAnalyticOpacity) {
    const Volume volume = linearRamp();
    const Scene plain = rampScene();
    const std::vector<int> off = renderGrey(volume, plain);
    // The rays through the whole depth: the unmodulated opacity 1 - (1 - alpha)^32.
    const int full = int(std::lround(255.0 * rayOpacity(1.0)));
    int x0 = 64, x1 = -1;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            if (std::abs(off[std::size_t(y) * 64 + x] - full) <= 1) x0 = std::min(x0, x), x1 = std::max(x1, x);
    ASSERT_GT(x1 - x0, 30) << "the volume does not fill the view";
    // Away from the x faces (a tenth of the width each side), where g = 4 exactly.
    const int margin = (x1 - x0) / 10;
    struct Ramp {
        double low, high, weight;
    };
    for (const Ramp ramp : {Ramp{0, 8, 0.5}, Ramp{2, 6, 0.5}, Ramp{3, 7, 0.25}, Ramp{0, 2, 1.0}, Ramp{6, 10, 0.0},
                            Ramp{5, 5, 0.0}, Ramp{3, 3, 1.0}, Ramp{7, 2, 1.0}}) {
        SCOPED_TRACE("low " + std::to_string(ramp.low) + ", high " + std::to_string(ramp.high));
        Scene scene = plain;
        scene.parameters["gradient_opacity"] = 1.0;
        scene.parameters["gradient_low"] = ramp.low;
        scene.parameters["gradient_high"] = ramp.high;
        const std::vector<int> got = renderGrey(volume, scene);
        const double expected = 255.0 * rayOpacity(ramp.weight);
        int checked = 0;
        double worst = 0.0;
        for (int y = 0; y < 64; ++y)
            for (int x = x0 + margin; x <= x1 - margin; ++x) {
                if (std::abs(off[std::size_t(y) * 64 + x] - full) > 1) continue;
                worst = std::max(worst, std::abs(got[std::size_t(y) * 64 + x] - expected));
                ++checked;
            }
        EXPECT_GT(checked, 500);
        EXPECT_LE(worst, 1.5) << "expected " << expected << " grey levels (weight " << ramp.weight << ")";
    }
}

// Off, the parameter changes nothing: the bounds are not read.
TEST_F(GradientOpacity, OffLeavesTheImageAlone) {
    const Volume volume = linearRamp();
    Scene scene = rampScene();
    const std::vector<int> plain = renderGrey(volume, scene);
    scene.parameters["gradient_low"] = 50.0;
    scene.parameters["gradient_high"] = 60.0;
    EXPECT_EQ(renderGrey(volume, scene), plain);
}

}  // namespace
}  // namespace voxlab::testing
