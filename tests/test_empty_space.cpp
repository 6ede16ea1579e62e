// Empty-space skipping (framework/include/render/voxlab/empty_space.h,
// shaders/voxlab/empty_space.glsl), checked three ways:
//  - the brick ranges against brute force over each brick and its apron,
//    and the brick flags against values and gradients computed here, on
//    the CPU, at random points of the bricks they call empty;
//  - the samples the shaders take (counted on the GPU) against a CPU walk of
//    the README's sample positions through bricks classified here;
//  - every ray-casting renderer's image with skipping on against the same
//    image with it off, within the grader's default tolerance (and in fact
//    within one grey level), while fewer samples are taken.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <nlohmann/json.hpp>

#include "support/cpu_sampling.h"
#include "support/bonsai_scene.h"
#include "support/gl_fixture.h"
#include "voxlab/camera.h"
#include "voxlab/empty_space.h"
#include "voxlab/gradients.h"
#include "voxlab/grading.h"
#include "voxlab/image_metrics.h"
#include "voxlab/renderer.h"
#include "voxlab/error.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"

namespace voxlab::testing {
namespace {

// A uint8 volume of low noise (0..40) holding a few solid balls (value 200)
// and one linear ramp, so that bricks are empty, full and mixed.
Volume blobVolume(glm::ivec3 dims, unsigned seed, glm::dvec3 spacing = glm::dvec3(1.0)) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> noise(0, 40);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    struct Ball {
        glm::dvec3 centre;
        double radius;
    };
    std::vector<Ball> balls;
    for (int i = 0; i < 3; ++i)
        balls.push_back({glm::dvec3(unit(rng), unit(rng), unit(rng)) * glm::dvec3(dims), 2.0 + 4.0 * unit(rng)});
    std::vector<std::uint8_t> bytes(std::size_t(dims.x) * dims.y * dims.z);
    std::size_t i = 0;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x, ++i) {
                int v = noise(rng);
                for (const Ball& b : balls)
                    if (glm::length(glm::dvec3(x, y, z) + 0.5 - b.centre) < b.radius) v = 200;
                if (z >= dims.z - 3) v = 40 + 215 * x / std::max(dims.x - 1, 1);  // a ramp in the last slabs
                bytes[i] = std::uint8_t(v);
            }
    return Volume(dims, VoxelType::UInt8, spacing, std::move(bytes), "blobs");
}

// A random continuous voxel coordinate inside brick b (clipped to the volume).
glm::dvec3 pointInBrick(const Volume& v, const BrickGrid& grid, glm::ivec3 b, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const glm::dvec3 lo = glm::dvec3(b * grid.brickSize);
    const glm::dvec3 hi = glm::min(lo + double(grid.brickSize), glm::dvec3(v.dims()));
    return lo + glm::dvec3(unit(rng), unit(rng), unit(rng)) * (hi - lo);
}

template <class F>
void forEachBrick(const BrickGrid& grid, F f) {
    for (int z = 0; z < grid.count.z; ++z)
        for (int y = 0; y < grid.count.y; ++y)
            for (int x = 0; x < grid.count.x; ++x) f(glm::ivec3(x, y, z));
}

TEST(BrickGrid, RangesAreTheExtremesOfEachBrickAndItsApron) {
    for (int brickSize : {1, 3, 8}) {
        const Volume v = blobVolume({21, 17, 13}, 7u + unsigned(brickSize));
        const BrickGrid grid = BrickGrid::build(v, brickSize);
        ASSERT_EQ(grid.count, (v.dims() + brickSize - 1) / brickSize);
        forEachBrick(grid, [&](glm::ivec3 b) {
            double lo = INFINITY, hi = -INFINITY;
            const glm::ivec3 from = glm::max(b * brickSize - 1, glm::ivec3(0));
            const glm::ivec3 to = glm::min((b + 1) * brickSize, v.dims() - 1);
            for (int z = from.z; z <= to.z; ++z)
                for (int y = from.y; y <= to.y; ++y)
                    for (int x = from.x; x <= to.x; ++x) {
                        lo = std::min(lo, v.value(x, y, z));
                        hi = std::max(hi, v.value(x, y, z));
                    }
            const glm::vec2 r = grid.range[grid.index(b)];
            EXPECT_EQ(r.x, lo) << "brick " << b.x << "," << b.y << "," << b.z << " of size " << brickSize;
            EXPECT_EQ(r.y, hi) << "brick " << b.x << "," << b.y << "," << b.z << " of size " << brickSize;
        });
    }
}

TEST(BrickGrid, EverySampleInABrickLiesInItsRange) {
    const Volume v = blobVolume({30, 26, 19}, 11u);
    const BrickGrid grid = BrickGrid::build(v, 8);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 20000; ++i) {
        const glm::dvec3 u = glm::dvec3(unit(rng), unit(rng), unit(rng)) * glm::dvec3(v.dims());
        const glm::vec2 r = grid.range[grid.index(grid.brickAt(u))];
        const double s = cpuTrilinear(v, u * v.spacing());
        ASSERT_GE(s, r.x - 1e-9) << "at " << u.x << "," << u.y << "," << u.z;
        ASSERT_LE(s, r.y + 1e-9) << "at " << u.x << "," << u.y << "," << u.z;
    }
}

TEST(BrickGrid, BuildsWithoutHoldingACopyOfTheVolume) {
    // 512 x 8 x 8 float: the rows of one brick layer only (a guard against
    // a per-voxel scratch buffer creeping back in is the memory figure in
    // docs/performance.md; here, that odd shapes and types work).
    std::vector<std::uint8_t> bytes(512 * 8 * 8 * sizeof(float));
    float* f = reinterpret_cast<float*>(bytes.data());
    for (std::size_t i = 0; i < 512 * 8 * 8; ++i) f[i] = float(i % 512) - 100.0f;
    const Volume v({512, 8, 8}, VoxelType::Float32, glm::dvec3(1.0), std::move(bytes));
    const BrickGrid grid = BrickGrid::build(v, 8);
    ASSERT_EQ(grid.count, glm::ivec3(64, 1, 1));
    EXPECT_EQ(grid.range[0], glm::vec2(-100.0f, -100.0f + 8.0f));    // x 0..8 (apron on the right)
    EXPECT_EQ(grid.range[63], glm::vec2(-100.0f + 503.0f, 411.0f));  // x 503..511
}

TEST(EmptySpace, BricksCalledEmptyHaveNoOpacityAnywhere) {
    const Volume v = blobVolume({40, 36, 32}, 5u);
    const BrickGrid grid = BrickGrid::build(v, 8);
    // Opaque only between 120 and 210 (the balls), with a sharp edge.
    const TransferFunction tf({{0.0, glm::vec3(0.0f), 0.0f}, {119.0, glm::vec3(0.0f), 0.0f},
                               {120.0, glm::vec3(1.0f, 0.5f, 0.2f), 0.4f}, {210.0, glm::vec3(1.0f), 0.4f},
                               {211.0, glm::vec3(1.0f), 0.0f}});
    const TransferFunctionTable table = tf.bake(v.minValue(), v.maxValue());
    const std::vector<std::uint8_t> visible = visibleBricks(grid, table);
    std::mt19937 rng(9);
    int empty = 0, full = 0;
    forEachBrick(grid, [&](glm::ivec3 b) {
        if (visible[grid.index(b)]) {
            ++full;
            return;
        }
        ++empty;
        for (int i = 0; i < 300; ++i) {
            const glm::dvec3 u = pointInBrick(v, grid, b, rng);
            ASSERT_EQ(table.lookup(cpuTrilinear(v, u * v.spacing())).a, 0.0f) << "empty brick " << b.x << "," << b.y << "," << b.z;
        }
    });
    EXPECT_GT(empty, 0);
    EXPECT_GT(full, 0);
    // A brick holding a ball voxel is visible.
    forEachBrick(grid, [&](glm::ivec3 b) {
        const glm::vec2 r = grid.range[grid.index(b)];
        if (r.y >= 200.0f) EXPECT_TRUE(visible[grid.index(b)]) << "brick " << b.x << "," << b.y << "," << b.z;
    });
}

TEST(BrickGrid, GradientBoundsHoldForEveryEstimator) {
    // Anisotropic spacing: gradients are per smallest spacing.
    const Volume v = blobVolume({30, 26, 22}, 31u, glm::dvec3(1.0, 1.5, 2.0));
    BrickGrid grid = BrickGrid::build(v, 8);
    grid.computeGradientBounds(v);
    ASSERT_EQ(grid.gradientBound.size(), grid.brickCount());
    const std::vector<glm::vec3> central = computeGradients(v, GradientEstimator::Central);
    const std::vector<glm::vec3> sobel = computeGradients(v, GradientEstimator::Sobel);
    // A per-voxel field read back trilinearly, as the GPU filters the gradient texture.
    const auto interpolate = [&](const std::vector<glm::vec3>& g, glm::dvec3 u) {
        const glm::dvec3 c = u - 0.5, lower = glm::floor(c), w = c - lower;
        glm::dvec3 sum(0.0);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
            const glm::ivec3 k = glm::clamp(glm::ivec3(lower) + o, glm::ivec3(0), v.dims() - 1);
            const double weight = (o.x ? w.x : 1 - w.x) * (o.y ? w.y : 1 - w.y) * (o.z ? w.z : 1 - w.z);
            sum += weight * glm::dvec3(g[(std::size_t(k.z) * v.dims().y + k.y) * v.dims().x + k.x]);
        }
        return sum;
    };
    std::mt19937 rng(12);
    forEachBrick(grid, [&](glm::ivec3 b) {
        const std::size_t i = grid.index(b);
        // The wide range holds every voxel two around the brick (brute force).
        const glm::ivec3 from = glm::max(b * 8 - 2, glm::ivec3(0)), to = glm::min((b + 1) * 8 + 1, v.dims() - 1);
        double lo = INFINITY, hi = -INFINITY;
        for (int z = from.z; z <= to.z; ++z)
            for (int y = from.y; y <= to.y; ++y)
                for (int x = from.x; x <= to.x; ++x) lo = std::min(lo, v.value(x, y, z)), hi = std::max(hi, v.value(x, y, z));
        EXPECT_EQ(grid.wideRange[i], glm::vec2(float(lo), float(hi)));
        for (int k = 0; k < 200; ++k) {
            const glm::dvec3 u = pointInBrick(v, grid, b, rng);
            // The gradient stage's central differences, per smallest spacing.
            const double stage = glm::length(cpuCentralGradient(v, u * v.spacing()));
            for (double g : {stage, glm::length(interpolate(central, u)), glm::length(interpolate(sobel, u))}) {
                ASSERT_LE(g, grid.gradientBound[i]) << "brick " << b.x << "," << b.y << "," << b.z;
            }
        }
    });
    // On a linear field the bound is the gradient itself: |(3, -2, 1)| in every brick.
    std::vector<std::uint8_t> bytes(20 * 20 * 20 * sizeof(float));
    float* f = reinterpret_cast<float*>(bytes.data());
    for (int z = 0; z < 20; ++z)
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 20; ++x) f[(z * 20 + y) * 20 + x] = float(3 * x - 2 * y + z);
    const Volume linear({20, 20, 20}, VoxelType::Float32, glm::dvec3(1.0), std::move(bytes));
    BrickGrid exact = BrickGrid::build(linear, 8);
    exact.computeGradientBounds(linear);
    for (float bound : exact.gradientBound) EXPECT_NEAR(bound, std::sqrt(14.0), 1e-3);
}

TEST(BrickGrid, TightGradientBoundsHoldForTheirEstimatorEverywhere) {
    // Bricks of 2 and 8 voxels, anisotropic spacing, points everywhere in
    // each brick (the outer ones reach the faces, where the stage clamps
    // its two positions): the stage's own estimate, computed here, is
    // within the bound for its estimator and the value within the range.
    const Volume v = blobVolume({30, 26, 22}, 37u, glm::dvec3(1.0, 1.5, 2.0));
    for (int size : {2, 8}) {
        for (GradientEstimator estimator : {GradientEstimator::Central, GradientEstimator::Sobel}) {
            BrickGrid grid = BrickGrid::build(v, size);
            grid.computeGradientBounds(v, estimator);
            BrickGrid loose = BrickGrid::build(v, size);
            loose.computeGradientBounds(v);
            ASSERT_EQ(grid.boundsFor, estimator);
            std::mt19937 rng(size * 10 + int(estimator));
            double tightSum = 0.0, looseSum = 0.0;
            forEachBrick(grid, [&](glm::ivec3 b) {
                const std::size_t i = grid.index(b);
                tightSum += grid.gradientBound[i], looseSum += loose.gradientBound[i];
                for (int k = 0; k < 60; ++k) {
                    const glm::dvec3 p = pointInBrick(v, grid, b, rng) * v.spacing();
                    const glm::dvec3 g = estimator == GradientEstimator::Central ? cpuCentralGradient(v, p)
                                                                                 : cpuSobelGradient(v, p);
                    ASSERT_LE(glm::length(g), grid.gradientBound[i])
                        << gradientEstimatorName(estimator) << ", bricks of " << size << ", brick " << b.x << ","
                        << b.y << "," << b.z;
                    const double value = cpuTrilinear(v, p);
                    ASSERT_GE(value, grid.wideRange[i].x - 1e-4);
                    ASSERT_LE(value, grid.wideRange[i].y + 1e-4);
                    // Nearest sampling: within twice the bound (EmptySpaceRule::gradientBoundScale).
                    if (estimator == GradientEstimator::Central) {
                        glm::dvec3 nearest;
                        for (int a = 0; a < 3; ++a) nearest[a] = cpuLineDerivative(v, p, a, true);
                        ASSERT_LE(glm::length(nearest * v.minSpacing()), 2.0 * grid.gradientBound[i])
                            << "nearest, bricks of " << size << ", brick " << b.x << "," << b.y << "," << b.z;
                    }
                }
            });
            // What the knowledge buys: on noise with solid balls, the bounds
            // are well below the bound for any estimator.
            EXPECT_LT(tightSum, 0.8 * looseSum) << gradientEstimatorName(estimator) << ", bricks of " << size;
        }
    }
}

TEST(EmptySpace, BricksCalledEmptyUnderThe2DTransferFunctionHaveNoOpacity) {
    const Volume v = blobVolume({40, 36, 32}, 21u);
    BrickGrid grid = BrickGrid::build(v, 8);
    // A narrow triangle at 120 (only steep edges reach it) and a box.
    Tf2dWidget triangle;
    triangle.kind = Tf2dWidget::Kind::Triangle;
    triangle.valueRange = glm::dvec2(120.0);
    triangle.radius = 0.05;
    Tf2dWidget box;
    box.kind = Tf2dWidget::Kind::Box;
    box.valueRange = {230.0, 255.0};
    box.gradientRange = {0.0, 1000.0};
    const std::vector<Tf2dWidget> widgets = {triangle, box};
    // The gradient bounds come first; without them the call says so.
    EXPECT_THROW(visibleBricks(grid, widgets), Error);
    grid.computeGradientBounds(v);
    const auto alpha = [&](double f, double g) {
        double keep = 1.0;
        for (const Tf2dWidget& w : widgets) {
            double a = 0.0;
            if (w.kind == Tf2dWidget::Kind::Box) {
                a = f >= w.valueRange.x && f <= w.valueRange.y && g >= w.gradientRange.x && g <= w.gradientRange.y
                        ? w.alpha
                        : 0.0;
            } else {
                const double d = std::abs(w.valueRange.x - f);
                a = g > 0.0 ? (d <= w.radius * g ? w.alpha * (1.0 - d / (w.radius * g)) : 0.0) : (d == 0.0 ? w.alpha : 0.0);
            }
            keep *= 1.0 - a;
        }
        return 1.0 - keep;
    };
    const std::vector<std::uint8_t> visible = visibleBricks(grid, widgets);
    std::mt19937 rng(4);
    int empty = 0;
    forEachBrick(grid, [&](glm::ivec3 b) {
        if (visible[grid.index(b)]) return;
        ++empty;
        for (int i = 0; i < 300; ++i) {
            const glm::dvec3 u = pointInBrick(v, grid, b, rng);
            ASSERT_EQ(alpha(cpuTrilinear(v, u * v.spacing()), glm::length(cpuCentralGradient(v, u * v.spacing()))), 0.0)
                << "empty brick " << b.x << "," << b.y << "," << b.z;
        }
    });
    EXPECT_GT(empty, 0);
    // Without widgets every brick is empty; a box over every value and
    // gradient makes every brick visible.
    EXPECT_EQ(std::count(visible.begin(), visible.end(), 0), empty);
    const std::vector<std::uint8_t> none = visibleBricks(grid, std::vector<Tf2dWidget>{});
    EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);
    Tf2dWidget everything = box;
    everything.valueRange = {-1e9, 1e9};
    everything.gradientRange = {0.0, 1e9};
    const std::vector<std::uint8_t> all = visibleBricks(grid, std::vector<Tf2dWidget>{everything});
    EXPECT_EQ(std::count(all.begin(), all.end(), 1), long(all.size()));
}

TEST(EmptySpace, BricksBelowAThresholdAreEmpty) {
    const Volume v = blobVolume({33, 29, 25}, 13u);
    const BrickGrid grid = BrickGrid::build(v, 8);
    const std::vector<std::uint8_t> visible = bricksReaching(grid, 150.0);
    std::mt19937 rng(8);
    forEachBrick(grid, [&](glm::ivec3 b) {
        if (visible[grid.index(b)]) return;
        for (int i = 0; i < 300; ++i) ASSERT_LT(cpuTrilinear(v, pointInBrick(v, grid, b, rng) * v.spacing()), 150.0);
    });
    const std::vector<std::uint8_t> none = bricksReaching(grid, 1000.0);
    EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);
}

class Skipping : public GlTest {};

// Per pixel of an oblique perspective view: the README's samples (t_entry
// + (m + 1/2) step within the box), the nearest voxel's value at each, and
// the brick each lies in.
struct SampleWalk {
    std::vector<std::vector<double>> values;        // per pixel, per sample
    std::vector<std::vector<glm::ivec3>> bricks;    // per pixel, per sample
};

SampleWalk walkSamples(const Volume& v, const Scene& scene, int brickSize) {
    const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
    const double step = scene.step * v.minSpacing();
    SampleWalk walk;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            glm::dvec3 o, d;
            cam.ray(x + 0.5, y + 0.5, &o, &d);
            double t0, t1;
            std::vector<double> values;
            std::vector<glm::ivec3> bricks;
            if (clipRayToBox(o, d, glm::dvec3(0.0), v.extent(), &t0, &t1)) {
                const int n = int(std::floor((t1 - t0) / step + 0.5));
                for (int m = 0; m < n; ++m) {
                    const glm::dvec3 u = (o + (t0 + (m + 0.5) * step) * d) / v.spacing();
                    values.push_back(clampedVoxel(v, glm::ivec3(glm::floor(u))));
                    bricks.push_back(glm::clamp(glm::ivec3(glm::floor(u / double(brickSize))), glm::ivec3(0),
                                                (v.dims() + brickSize - 1) / brickSize - 1));
                }
            }
            walk.values.push_back(values);
            walk.bricks.push_back(bricks);
        }
    return walk;
}

Scene obliqueScene(const std::string& renderer, int size) {
    Scene scene;
    scene.renderer = renderer;
    scene.camera.azimuth = 37.0;
    scene.camera.elevation = 23.0;
    scene.camera.projection = Projection::Perspective;
    scene.width = scene.height = size;
    scene.step = 0.7;
    return scene;
}

TEST_F(Skipping, FirstHitTakesExactlyTheSamplesOfVisibleBricksUpToTheHit) {
    const Volume v = blobVolume({40, 36, 32}, 17u);
    engine().setVolume(v);
    Scene scene = obliqueScene("firsthit", 48);
    scene.interpolation = Interpolation::Nearest;
    const double threshold = 150.0;
    scene.parameters["threshold"] = threshold;

    // The bricks (and their one-voxel apron) that hold a voxel >= threshold, found here.
    const int b = kBrickSize;
    const glm::ivec3 count = (v.dims() + b - 1) / b;
    const auto visible = [&](glm::ivec3 brick) {
        const glm::ivec3 from = glm::max(brick * b - 1, glm::ivec3(0)), to = glm::min((brick + 1) * b, v.dims() - 1);
        for (int z = from.z; z <= to.z; ++z)
            for (int y = from.y; y <= to.y; ++y)
                for (int x = from.x; x <= to.x; ++x)
                    if (v.value(x, y, z) >= threshold) return true;
        return false;
    };
    std::vector<char> isVisible(std::size_t(count.x) * count.y * count.z);
    for (int z = 0; z < count.z; ++z)
        for (int y = 0; y < count.y; ++y)
            for (int x = 0; x < count.x; ++x) isVisible[(std::size_t(z) * count.y + y) * count.x + x] = visible({x, y, z});
    const SampleWalk walk = walkSamples(v, scene, b);
    // The walk of voxlab/runs.glsl: from the first sample in a visible
    // brick, a run of one brick's length in samples (the smallest brick
    // side over the step, both in world units), then look again.
    const glm::dvec3 brickExtent = double(b) * v.spacing();
    const double minSpacing = std::min({v.spacing().x, v.spacing().y, v.spacing().z});
    const int perRun = std::max(1, int(std::min({brickExtent.x, brickExtent.y, brickExtent.z}) / (scene.step * minSpacing)));
    double expected = 0.0, all = 0.0;
    for (std::size_t p = 0; p < walk.values.size(); ++p) {
        const std::size_t n = walk.values[p].size();
        all += double(n);
        const auto visibleAt = [&](std::size_t m) {
            const glm::ivec3 k = walk.bricks[p][m];
            return isVisible[(std::size_t(k.z) * count.y + k.y) * count.x + k.x] != 0;
        };
        bool hit = false;
        for (std::size_t m = 0; m < n && !hit;) {
            while (m < n && !visibleAt(m)) ++m;
            for (const std::size_t end = std::min(m + perRun, n); m < end && !hit; ++m) {
                expected += 1.0;
                hit = walk.values[p][m] >= threshold;  // the hit ends the ray
            }
        }
    }
    scene.skipEmptySpace = true;
    const double taken = engine().countSamples(scene);
    ASSERT_GT(expected, 0.0);
    ASSERT_LT(expected, 0.5 * all) << "the volume should be mostly empty for this threshold";
    // Samples within a hair of a voxel or brick face may fall either way.
    EXPECT_NEAR(taken, expected, 0.002 * expected + 4.0) << "of " << all << " samples in all";

    // Without skipping, a renderer that reads every sample (the average)
    // takes the README's count exactly.
    scene.renderer = "average";
    scene.parameters.clear();
    scene.skipEmptySpace = false;
    EXPECT_EQ(engine().countSamples(scene), all);
}

struct SkipCase {
    const char* name;
    const char* renderer;
    std::vector<std::pair<const char*, double>> parameters;
    Interpolation interpolation = Interpolation::Trilinear;
    bool transferFunction = false;
    bool transferFunction2D = false;
    bool cut = false;
    bool expectFewerSamples = true;
};

class SkippingKeepsTheImage : public GlTest, public ::testing::WithParamInterface<SkipCase> {};

TEST_P(SkippingKeepsTheImage, OnBonsai) {
    static const Volume bonsai = loadVolume(datasetPath("bonsai.nrrd"));
    const SkipCase& c = GetParam();
    engine().setVolume(bonsai);
    Scene scene = bonsaiScene({c.renderer, c.parameters, c.interpolation, c.transferFunction, c.transferFunction2D});
    if (c.cut) {
        CuttingPlane cut;
        cut.normal = glm::dvec3(1.0, 0.2, 0.0);
        cut.otherRenderer = "mip";
        scene.cuttingPlane = cut;
    }
    scene.skipEmptySpace = false;
    const Image off = asPng(engine().render(scene));
    scene.skipEmptySpace = true;
    const Image on = asPng(engine().render(scene));
    const ImageMetrics m = compareForGrading(off, on, Tolerance{});
    EXPECT_LE(toleranceRatio(m, Tolerance{}), 1.0) << c.name << ": " << toJson(m).dump();
    // The same samples composited in runs ("over" of partial sums, and
    // early termination where the whole-ray loop stops: voxlab/runs.glsl)
    // round differently by far less than a level: at most one level apart.
    EXPECT_LE(m.maxDifference, 1.0) << c.name;

    if (!c.cut) {
        scene.skipEmptySpace = false;
        const double all = engine().countSamples(scene);
        scene.skipEmptySpace = true;
        const double taken = engine().countSamples(scene);
        if (c.expectFewerSamples)
            EXPECT_LT(taken, 0.8 * all) << c.name << ": skipping should leave out at least a fifth of the samples";
        else
            EXPECT_LE(taken, all) << c.name;
    }
}

const SkipCase kSkipCases[] = {
    {"composite", "composite", {}, Interpolation::Trilinear, true},
    {"composite_hardware", "composite", {}, Interpolation::Hardware, true},
    {"composite_nearest_preclassified_shaded",
     "composite",
     {{"preclassify", 1}, {"shading", 1}},
     Interpolation::Nearest,
     true},
    {"composite_back_to_front_jitter", "composite", {{"back_to_front", 1}, {"jitter", 1}}, Interpolation::Trilinear, true},
    {"composite_no_early_termination", "composite", {{"early_termination", 1.0}}, Interpolation::Trilinear, true},
    {"composite_cut", "composite", {}, Interpolation::Trilinear, true, false, true},
    {"tf2d", "tf2d", {}, Interpolation::Trilinear, false, true},
    // The GPU's filtering: fixed-point weights, within the bounds' margin.
    {"tf2d_shaded_hardware", "tf2d", {{"shading", 1}}, Interpolation::Hardware, false, true},
    {"tf2d_nearest", "tf2d", {}, Interpolation::Nearest, false, true},
    {"tf2d_precomputed_gradients", "tf2d", {{"precomputed_gradients", 1}}, Interpolation::Trilinear, false, true},
    {"tf2d_shaded_sobel", "tf2d", {{"shading", 1}, {"sobel", 1}}, Interpolation::Trilinear, false, true},
    {"iso", "iso", {{"isovalue", 100}}},
    {"iso_depth_no_refinement", "iso", {{"isovalue", 60}, {"depth", 1}, {"refinement_steps", 0}}},
    {"firsthit", "firsthit", {{"threshold", 120}}},
    {"firsthit_depth", "firsthit", {{"threshold", 60}, {"depth", 1}}, Interpolation::Hardware},
    {"mip", "mip", {}},
    {"mip_hardware", "mip", {}, Interpolation::Hardware},
    {"minip", "minip", {}, Interpolation::Trilinear, false, false, false, false},
    {"slab_mip", "slab_mip", {{"thickness", 40}}, Interpolation::Trilinear, false, false, false, false},
    {"average", "average", {}, Interpolation::Trilinear, false, false, false, false},
};

INSTANTIATE_TEST_SUITE_P(Renderers, SkippingKeepsTheImage, ::testing::ValuesIn(kSkipCases),
                         [](const ::testing::TestParamInfo<SkipCase>& info) { return std::string(info.param.name); });

TEST(SkippingScene, IsOnByDefaultAndReadFromTheSceneFile) {
    const nlohmann::json j = {{"dataset", "phantom:sphere:16"}, {"sampling", {{"skip_empty_space", false}}}};
    const Scene off = Scene::fromJson(j, "scene.json", "");
    EXPECT_FALSE(off.skipEmptySpace);
    EXPECT_FALSE(Scene::fromJson(off.toJson(), "again", "").skipEmptySpace);
    EXPECT_TRUE(Scene::fromJson({{"dataset", "phantom:sphere:16"}}, "scene.json", "").skipEmptySpace);
    nlohmann::json bad = j;
    bad["sampling"]["skip_empty_space"] = "yes";
    try {
        Scene::fromJson(bad, "scene.json", "");
        FAIL() << "a string was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("sampling.skip_empty_space"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace voxlab::testing
