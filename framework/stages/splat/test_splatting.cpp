// Splatting (splatting.h, the splat stage, the splat renderer) against
// oracles that do not use its code:
//  - one voxel, analytically: its splat's matter, L = u ln(1 - a) /
//    ln(1 - alpha) per pixel (u the unit length, a the pixel's opacity),
//    summed over the image times the pixel's area, is the voxel's volume V
//    less what the cut at 3 sigma leaves out (exp(-4.5) of it); and its
//    spread, the mean of r^2 weighted by L, is the truncated 2D Gaussian's,
//    2 sigma^2 (1 - (1 + R^2/(2 sigma^2)) e^(-R^2/(2 sigma^2))) / (1 - e^(-R^2/(2 sigma^2))), R = 3 sigma:
//    the blur grows with the kernel's radius as predicted;
//  - the walk: for every pair of voxels that differ on at most two axes,
//    the one farther along the view is drawn first (the three-axis
//    diagonals are slice splatting's known approximation);
//  - composite at step 1 (one sample per voxel, as one splat per voxel):
//    mean SSIM on bonsai and tooth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>

#include "support/gl_fixture.h"
#include "voxlab/image_metrics.h"
#include "voxlab/splatting.h"
#include "voxlab/stage_library.h"

namespace voxlab::testing {
namespace {

constexpr int kN = 21;  // the voxel in the middle of a box wide enough for any footprint

Volume oneVoxel(glm::dvec3 spacing) {
    std::vector<float> values(kN * kN * kN, 0.0f);
    values[kN / 2 + kN * (kN / 2 + kN * (kN / 2))] = 1.0f;
    std::vector<std::uint8_t> bytes(values.size() * 4);
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return Volume(glm::ivec3(kN), VoxelType::Float32, spacing, bytes, "one voxel");
}

struct Footprint {
    double matter = 0.0, spread = 0.0;  // the integral of L, and the mean r^2
};

// Renders the single voxel from +z, orthographic, zoomed so that the image
// spans about +-9.5 world units around it (the widest footprint here reaches
// 6) with pixels of about 0.06, and measures its footprint.
Footprint measure(RenderEngine& engine, const Volume& v, double radius, double alpha) {
    Scene s;
    s.renderer = "splat";
    s.camera.view = "+z";
    s.camera.projection = Projection::Orthographic;
    s.camera.zoom = 0.5 * glm::length(v.extent()) / 9.5;
    s.width = s.height = 320;
    s.transferFunction = TransferFunction({{0.0, glm::vec3(1.0f), 0.0f}, {1.0, glm::vec3(1.0f), float(alpha)}});
    s.parameters = {{"radius", radius}};
    engine.setVolume(v);
    const Image image = engine.render(s);
    const Camera cam = Camera::make(s.camera, v.extent(), s.width, s.height);
    const glm::dvec3 centre = (kN / 2 + 0.5) * v.spacing();
    const double pixelArea = cam.pixelScale * cam.pixelScale, u = v.minSpacing();
    Footprint f;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const double a = image.at(x, y).r;  // white over black: the pixel's opacity
            if (a <= 0.0) continue;
            const double L = u * std::log(1.0 - a) / std::log(1.0 - alpha);
            glm::dvec3 o, d;
            cam.ray(x + 0.5, y + 0.5, &o, &d);
            const glm::dvec3 off = o - centre;
            const double r2 = off.x * off.x + off.y * off.y;
            f.matter += L * pixelArea, f.spread += L * pixelArea * r2;
        }
    f.spread /= f.matter;
    return f;
}

class Splatting : public GlTest {};

TEST_F(Splatting, OneVoxelsFootprintHoldsItsMatterAndSpreadsAsItsKernel) {
    const double cut = std::exp(-4.5);  // the 2D Gaussian's mass beyond 3 sigma
    for (const glm::dvec3 spacing : {glm::dvec3(1.0), glm::dvec3(1.5, 1.0, 2.0)}) {
        const Volume v = oneVoxel(spacing);
        const double volume = spacing.x * spacing.y * spacing.z;
        for (double radius : {0.5, 1.0, 2.0}) {
            const Footprint f = measure(engine(), v, radius, 0.05);
            const double sigma = radius * v.minSpacing(), k = 4.5;
            const double spread = 2.0 * sigma * sigma * (1.0 - (1.0 + k) * std::exp(-k)) / (1.0 - std::exp(-k));
            std::printf("spacing %.1f %.1f %.1f, radius %.1f: matter %.4f of %.4f, spread %.4f of %.4f (world^2)\n",
                        spacing.x, spacing.y, spacing.z, radius, f.matter, volume * (1.0 - cut), f.spread, spread);
            EXPECT_NEAR(f.matter / (volume * (1.0 - cut)), 1.0, 0.02) << radius;
            EXPECT_NEAR(f.spread / spread, 1.0, 0.03) << radius;
        }
    }
}

TEST(SplatOrder, EveryVoxelIsDrawnBeforeItsNeighboursInFront) {
    const Volume v = loadVolume("phantom:ramp-x:6");  // every value shown by the function below
    const TransferFunction all({{0.0, glm::vec3(1.0f), 0.5f}});
    std::mt19937 rng(90);
    std::normal_distribution<double> normal;
    for (int trial = 0; trial < 200; ++trial) {
        const glm::dvec3 d(normal(rng), normal(rng), normal(rng));
        const std::vector<glm::vec4> points = splatPoints(v, all, cppStages().splatOrder(d));
        ASSERT_EQ(points.size(), 216u);
        std::map<std::tuple<int, int, int>, std::size_t> drawn;
        for (std::size_t n = 0; n < points.size(); ++n)
            drawn[{int(points[n].x), int(points[n].y), int(points[n].z)}] = n;
        for (const auto& [p, n] : drawn)
            for (const auto& [q, m] : drawn) {
                const glm::dvec3 e(std::get<0>(q) - std::get<0>(p), std::get<1>(q) - std::get<1>(p),
                                   std::get<2>(q) - std::get<2>(p));
                const int axes = (e.x != 0) + (e.y != 0) + (e.z != 0);
                if (axes == 0 || axes == 3 || glm::length(e) > 1.5) continue;  // neighbours on one or two axes
                if (glm::dot(e, d) > 1e-12) EXPECT_LT(m, n) << "the farther voxel is drawn after a nearer one";
            }
    }
}

TEST_F(Splatting, ImagesAgreeWithCompositingOneSamplePerVoxel) {
    for (const char* name : {"bonsai", "tooth"}) {
        const Volume v = loadVolume(datasetPath(std::string(name) + ".nrrd"));
        Scene s;
        s.camera.azimuth = 35.0, s.camera.elevation = 20.0;
        s.width = s.height = 160;
        s.step = 1.0;
        s.transferFunction = TransferFunction::load(datasetPath(std::string("tf/") + name + ".json"));
        engine().setVolume(v);
        s.renderer = "composite";
        const Image rayCast = engine().render(s);
        s.renderer = "splat";
        const Image splatted = engine().render(s);
        const double mean = ssim(rayCast, splatted).mean;
        std::printf("%s: splatting against composite at step 1, mean SSIM %.4f\n", name, mean);
        EXPECT_GT(mean, 0.9) << name;
    }
}

}  // namespace
}  // namespace voxlab::testing
