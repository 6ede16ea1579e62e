// Local ambient occlusion (the ambient_occlusion stage, used by composite
// with `ambient_occlusion` on), against a bowl composited on the CPU.
//
// The phantom: a hemispherical shell (radii 9 and 13 voxels, opening
// upwards) in a 36^3 float volume, seen from straight above, orthographic.
// The transfer function is white with opacity equal to the value (0 outside
// the shell, 1 inside it), shading off. The oracle composites every pixel's
// ray on the CPU from the definitions in the README and the stage's handout:
// the GPU's sample positions (t_entry + (m + 1/2) step on the ray clipped to
// the box), trilinear values (support/cpu_sampling.h), opacity correction,
// front to back, and each sample's colour 1 - strength * o(p), with o the
// mean clamped opacity at the 14 points radius away (axes and unit
// diagonals), outside the box counting 0.
//
// Tolerance: 2 grey levels. The GPU reads the transfer function from a
// table baked to 0.5/255 and composites up to 80 samples in float; the image
// is 8-bit. Ignoring the occlusion is off by up to 200 levels inside the
// bowl, a radius in voxels of the wrong axis or a missing diagonal by tens.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "support/cpu_sampling.h"
#include "support/gl_fixture.h"
#include "voxlab/camera.h"

namespace voxlab::testing {
namespace {

constexpr int kN = 36;
constexpr double kStrength = 0.9, kRadius = 4.0, kStep = 0.5;

Volume bowl() {
    std::vector<float> values(std::size_t(kN) * kN * kN);
    const glm::dvec3 centre(18.0, 18.0, 22.0);
    std::size_t idx = 0;
    for (int k = 0; k < kN; ++k)
        for (int j = 0; j < kN; ++j)
            for (int i = 0; i < kN; ++i) {
                const glm::dvec3 p = glm::dvec3(i, j, k) + 0.5;
                const double r = glm::length(p - centre);
                values[idx++] = (r >= 9.0 && r <= 13.0 && p.z <= centre.z) ? 1.0f : 0.0f;
            }
    std::vector<std::uint8_t> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return Volume(glm::ivec3(kN), VoxelType::Float32, glm::dvec3(1.0), bytes, "bowl");
}

double opacityAt(const Volume& v, glm::dvec3 q) {
    const glm::dvec3 e = v.extent();
    if (q.x < 0 || q.y < 0 || q.z < 0 || q.x > e.x || q.y > e.y || q.z > e.z) return 0.0;
    return std::clamp(cpuTrilinear(v, q), 0.0, 1.0);  // the transfer function: opacity = value
}

// The handout's o(p): the mean opacity at the 14 points `radius` away.
double occlusion(const Volume& v, glm::dvec3 p, double radius) {
    double sum = 0.0;
    for (int axis = 0; axis < 3; ++axis)
        for (double sign : {-1.0, 1.0}) {
            glm::dvec3 d(0.0);
            d[axis] = sign;
            sum += opacityAt(v, p + radius * d);
        }
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 d(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0);
        sum += opacityAt(v, p + radius * d / std::sqrt(3.0));
    }
    return sum / 14.0;
}

// The pixel's grey level composited on the CPU (white over black).
double cpuPixel(const Volume& v, const Camera& cam, int x, int y, bool ao) {
    glm::dvec3 o, d;
    cam.ray(x + 0.5, y + 0.5, &o, &d);
    double t0 = -1e300, t1 = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < 0.0 || o[a] > v.extent()[a]) return 0.0;
            continue;
        }
        const double ta = -o[a] / d[a], tb = (v.extent()[a] - o[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb)), t1 = std::min(t1, std::max(ta, tb));
    }
    t0 = std::max(t0, 0.0);
    double colour = 0.0, opacity = 0.0;
    for (double t = t0 + 0.5 * kStep; t < t1; t += kStep) {
        const glm::dvec3 p = o + t * d;
        const double alpha = std::clamp(cpuTrilinear(v, p), 0.0, 1.0);
        if (alpha <= 0.0) continue;
        const double a = 1.0 - std::pow(1.0 - alpha, kStep);
        const double c = ao ? 1.0 - kStrength * occlusion(v, p, kRadius) : 1.0;
        colour += (1.0 - opacity) * a * c;
        opacity += (1.0 - opacity) * a;
    }
    return 255.0 * colour;
}

class AmbientOcclusion : public GlTest {};

TEST_F(AmbientOcclusion, TheBowlDarkensAsTheCpuComputes) {
    const Volume volume = bowl();
    Scene scene;
    scene.renderer = "composite";
    scene.camera.view = "-z";
    scene.camera.projection = Projection::Orthographic;
    scene.width = scene.height = 48;
    scene.step = kStep;
    scene.interpolation = Interpolation::Trilinear;
    scene.transferFunction = TransferFunction({{0.0, glm::vec3(1.0f), 0.0f}, {1.0, glm::vec3(1.0f), 1.0f}});
    scene.parameters = {{"early_termination", 1.0}, {"ambient_occlusion", 1.0}, {"ao_radius", kRadius},
                        {"ao_strength", kStrength}};
    const std::vector<int> gpu = renderGrey(volume, scene);
    const Camera cam = Camera::make(scene.camera, volume.extent(), scene.width, scene.height);
    double worst = 0.0, darkest = 255.0, lightest = 0.0;
    int hits = 0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            const double expected = cpuPixel(volume, cam, x, y, true);
            worst = std::max(worst, std::abs(gpu[std::size_t(y) * scene.width + x] - expected));
            const double plain = cpuPixel(volume, cam, x, y, false);
            if (plain > 100.0) {  // the ray meets the bowl
                ++hits;
                darkest = std::min(darkest, expected / plain), lightest = std::max(lightest, expected / plain);
            }
        }
    std::printf("bowl: %d pixels on the bowl, occlusion keeps %.2f to %.2f of the light; worst pixel %.2f levels\n",
                hits, darkest, lightest, worst);
    EXPECT_GT(hits, 400);
    EXPECT_LT(darkest, 0.6) << "the inside of the bowl should be darkened clearly";
    EXPECT_GT(lightest - darkest, 0.2) << "the rim and the inside should differ";
    EXPECT_LE(worst, 2.0);
}

}  // namespace
}  // namespace voxlab::testing
