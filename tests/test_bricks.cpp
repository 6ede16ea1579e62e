// Bricked rendering (framework/include/render/voxlab/volume_bricks.h,
// shaders/voxlab/bricks.glsl), checked against independent oracles:
//  - the plan: every voxel owned by exactly one brick, each texture its
//    brick plus the apron clipped to the volume, within the texture limit
//    and the budget; a budget too small is a one-line error;
//  - the visibility order against rays walked on the CPU: for random eyes
//    and rays (perspective and orthographic), the bricks a ray passes
//    through, found by stepping along it, come in the order's order;
//  - every ray-casting renderer's image of a bricked volume (a budget that
//    forces 18 bricks, 11 of them on the GPU at once) against the same
//    scene unbricked, with and without empty-space skipping, within one
//    grey level;
//  - bricks that stay on the GPU: a settled camera uploads nothing, a
//    turning one only the bricks the pool cannot hold (counted against the
//    bound that arithmetic gives), and bricks out of view or empty are
//    neither drawn nor uploaded, with the image unchanged;
//  - a volume longer than the largest texture (2100 x 128 x 128), which has
//    no unbricked render, against MIP and first hit computed here on the CPU
//    from the voxels;
//  - what cannot be drawn in bricks says so in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <nlohmann/json.hpp>

#include "support/bonsai_scene.h"
#include "support/gl_fixture.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/grading.h"
#include "voxlab/image_metrics.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"
#include "voxlab/volume_bricks.h"

namespace voxlab::testing {
namespace {

constexpr std::size_t kMiB = std::size_t(1) << 20;

TEST(BrickPlan, AVolumeThatFitsIsOneBrickWithoutAnApron) {
    const BrickLayout l = planBricks({256, 256, 178}, 1, 2048, 64 * kMiB);
    ASSERT_EQ(l.bricks.size(), 1u);
    EXPECT_FALSE(l.bricked());
    EXPECT_EQ(l.bricks[0].textureOrigin, glm::ivec3(0));
    EXPECT_EQ(l.bricks[0].textureSize, glm::ivec3(256, 256, 178));
}

TEST(BrickPlan, BricksOwnEveryVoxelOnceAndFitTheLimits) {
    struct Case {
        glm::ivec3 dims;
        int bytes, maxSize;
        std::size_t budget;
    };
    const Case cases[] = {{{2100, 128, 128}, 1, 2048, 1024 * kMiB},  // too long for one texture
                          {{256, 256, 256}, 1, 2048, 2 * kMiB},      // larger than the budget
                          {{301, 97, 53}, 2, 64, 64 * kMiB},         // both, odd sizes
                          {{1024, 1024, 1024}, 1, 2048, 256 * kMiB}};
    for (const Case& c : cases) {
        const BrickLayout l = planBricks(c.dims, c.bytes, c.maxSize, c.budget);
        EXPECT_TRUE(l.bricked());
        ASSERT_EQ(l.bricks.size(), std::size_t(l.count.x * l.count.y * l.count.z));
        // Ownership along each axis: the bricks' ranges tile [0, dims) once.
        const std::size_t voxels = std::size_t(c.dims.x) * c.dims.y * c.dims.z;
        const bool small = voxels <= 4u << 20;  // every voxel's owners counted
        std::vector<int> owners(small ? voxels : 0, 0);
        for (const VolumeBrick& b : l.bricks) {
            for (int a = 0; a < 3; ++a) {
                EXPECT_LT(b.lo[a], b.hi[a]);
                EXPECT_EQ(b.textureOrigin[a], std::max(b.lo[a] - kTextureBrickApron, 0));
                EXPECT_EQ(b.textureOrigin[a] + b.textureSize[a], std::min(b.hi[a] + kTextureBrickApron, c.dims[a]));
                EXPECT_LE(b.textureSize[a], c.maxSize);
            }
            EXPECT_EQ(b.bytes, std::size_t(b.textureSize.x) * b.textureSize.y * b.textureSize.z * c.bytes);
            EXPECT_LE(b.bytes, c.budget);
            if (small)
                for (int z = b.lo.z; z < b.hi.z; ++z)
                    for (int y = b.lo.y; y < b.hi.y; ++y)
                        for (int x = b.lo.x; x < b.hi.x; ++x) ++owners[(std::size_t(z) * c.dims.y + y) * c.dims.x + x];
        }
        if (small)
            EXPECT_TRUE(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));
        else  // the large case: the ranges along each axis meet end to end
            for (int a = 0; a < 3; ++a) EXPECT_EQ(l.bricks.back().hi[a], c.dims[a]);
        EXPECT_GE(l.resident, 1u);
        EXPECT_LE(l.resident * 1, l.bricks.size());
        std::size_t largest = 0;
        for (const VolumeBrick& b : l.bricks) largest = std::max(largest, b.bytes);
        EXPECT_LE(std::min(l.resident, l.bricks.size()) * largest, std::max(c.budget, largest));
    }
}

TEST(BrickPlan, AVolumeLargerThanTheBudgetKeepsEightBricksOnTheGpu) {
    // 16 MiB of voxels in 12 MiB: bricks small enough that at least eight
    // fit at once, so that a frame finds most of its bricks still there.
    const BrickLayout l = planBricks({256, 256, 256}, 1, 2048, 12 * kMiB);
    std::size_t largest = 0;
    for (const VolumeBrick& b : l.bricks) largest = std::max(largest, b.bytes);
    EXPECT_GE(l.resident, kResidentBricksAimed);
    EXPECT_LT(l.resident, l.bricks.size());
    EXPECT_LE(l.resident * largest, 12 * kMiB);
    // Where bricks of 16 voxels a side cannot make eight fit, as many as fit.
    const BrickLayout tight = planBricks({256, 256, 256}, 4, 2048, 2 * 22 * 22 * 22 * 4);
    EXPECT_GE(tight.resident, 1u);
    EXPECT_LT(tight.resident, kResidentBricksAimed);
    // Aiming for one: bricks as large as fit, the fewest passes (a software
    // renderer and a volume over twice the budget).
    EXPECT_EQ(residentBricksAimed(16 * kMiB, 4 * kMiB, true), 1u);
    EXPECT_EQ(residentBricksAimed(16 * kMiB, 8 * kMiB, true), kResidentBricksAimed);
    EXPECT_EQ(residentBricksAimed(16 * kMiB, 4 * kMiB, false), kResidentBricksAimed);
    const BrickLayout few = planBricks({256, 256, 256}, 1, 2048, 4 * kMiB, 1);
    EXPECT_EQ(few.bricks.size(), 8u);
    EXPECT_EQ(few.resident, 1u);
}

TEST(BrickPlan, ABudgetThatHoldsNoBrickIsAOneLineError) {
    try {
        planBricks({512, 512, 512}, 4, 2048, 4096);
        FAIL() << "no error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_NE(what.find("GPU memory budget of 0 MiB"), std::string::npos) << what;
        EXPECT_NE(what.find("--gpu-memory"), std::string::npos) << what;
    }
}

// The bricks a ray meets, in the order it meets them: found by stepping
// along it in steps far shorter than a brick (a corner it only grazes may
// be missed, which leaves the order of the others as it is).
std::vector<int> bricksAlong(const BrickLayout& l, const glm::dvec3& dims, glm::dvec3 origin, glm::dvec3 dir) {
    std::vector<int> seen;
    for (double t = 0.0; t < 4.0 * glm::length(dims); t += 0.05) {
        const glm::dvec3 p = origin + t * dir;
        if (glm::any(glm::lessThan(p, glm::dvec3(0.0))) || glm::any(glm::greaterThanEqual(p, dims))) continue;
        const glm::ivec3 index = glm::ivec3(glm::floor(p)) / l.core;
        const int b = (index.z * l.count.y + index.y) * l.count.x + index.x;
        if (seen.empty() || seen.back() != b) seen.push_back(b);
    }
    return seen;
}

TEST(BrickOrder, EveryRayMeetsTheBricksInTheOrdersOrder) {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int trial = 0; trial < 60; ++trial) {
        const glm::ivec3 dims(40 + int(60 * unit(rng)), 40 + int(60 * unit(rng)), 40 + int(60 * unit(rng)));
        const BrickLayout l = planBricks(dims, 1, 24, 64 * kMiB);  // bricks of at most 18 voxels
        const glm::dvec3 d(dims);
        const bool orthographic = trial % 3 == 0;
        // An eye outside the box, or (one in four) inside it.
        glm::dvec3 eye = trial % 4 == 1 ? glm::dvec3(unit(rng), unit(rng), unit(rng)) * d
                                        : d * 0.5 + glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)) - 0.5) *
                                                        glm::length(d) * (1.0 + unit(rng));
        const glm::dvec3 forward = glm::normalize(d * 0.5 - eye + (glm::dvec3(unit(rng), unit(rng), unit(rng)) - 0.5));
        const std::vector<int> order = frontToBackOrder(l, eye, forward, orthographic);
        std::vector<int> rank(order.size());
        for (std::size_t i = 0; i < order.size(); ++i) rank[std::size_t(order[i])] = int(i);
        for (int r = 0; r < 40; ++r) {
            const glm::dvec3 target = glm::dvec3(unit(rng), unit(rng), unit(rng)) * d;
            glm::dvec3 origin = eye, dir = glm::normalize(target - eye);
            if (orthographic) dir = forward, origin = target - forward * 2.0 * glm::length(d);
            const std::vector<int> met = bricksAlong(l, d, origin, dir);
            for (std::size_t k = 1; k < met.size(); ++k)
                ASSERT_LT(rank[std::size_t(met[k - 1])], rank[std::size_t(met[k])])
                    << "trial " << trial << " ray " << r << ": brick " << met[k - 1] << " then " << met[k];
        }
    }
}

struct BrickCase {
    const char* name;
    const char* renderer;
    std::vector<std::pair<const char*, double>> parameters;
    Interpolation interpolation = Interpolation::Trilinear;
    bool transferFunction = false;
    bool transferFunction2D = false;
    Projection projection = Projection::Perspective;
    bool sameSamples = true;  // bricked, every sample is taken once (see below)
};

void PrintTo(const BrickCase& c, std::ostream* os) { *os << c.name; }

class BrickedKeepsTheImage : public GlTest, public ::testing::WithParamInterface<BrickCase> {};

TEST_P(BrickedKeepsTheImage, OnBonsai) {
    static const Volume bonsai = loadVolume(datasetPath("bonsai.nrrd"));
    const BrickCase& c = GetParam();
    engine().setVolume(bonsai);
    Scene scene = bonsaiScene({c.renderer, c.parameters, c.interpolation, c.transferFunction, c.transferFunction2D,
                               c.projection});
    for (bool skipping : {false, true}) {
        scene.skipEmptySpace = skipping;
        scene.gpuMemoryMiB.reset();
        const Image whole = asPng(engine().render(scene));
        ASSERT_FALSE(engine().brickLayout().bricked());
        // 16 MiB of voxels in 12 MiB: 2x3x3 bricks, 11 on the GPU at a
        // time, so that a frame uploads some of its bricks again.
        scene.gpuMemoryMiB = 12.0;
        const Image bricked = asPng(engine().render(scene));
        ASSERT_EQ(engine().brickLayout().bricks.size(), 18u);
        EXPECT_EQ(engine().brickLayout().resident, 11u);
        const ImageMetrics m = compareForGrading(whole, bricked, Tolerance{});
        EXPECT_LE(m.maxDifference, 1.0) << c.name << (skipping ? " with skipping" : "") << ": " << toJson(m).dump();
        double lit = 0.0;
        for (std::size_t i = 0; i < whole.rgba.size(); i += 4) lit += whole.rgba[i] + whole.rgba[i + 1];
        EXPECT_GT(lit, 10.0) << c.name << ": the image is blank, so it proves nothing";
        // The samples, counted on the GPU. A value renderer's walk over the
        // whole ray without skipping is cut at the bricks' faces and takes
        // the same samples. The others may take a few more or fewer, at the
        // same positions: with skipping, runs end at a brick's face instead of
        // running on into the empty brick behind it; compositing (when the
        // opacity reaches the threshold within a brick's part) takes the last
        // part again one sample at a time, as runs.glsl explains; the
        // isosurface takes one sample before each brick's face again.
        scene.gpuMemoryMiB.reset();
        const double all = engine().countSamples(scene);
        scene.gpuMemoryMiB = 12.0;
        const double inBricks = engine().countSamples(scene);
        const std::string what = std::string(c.name) + (skipping ? " with skipping" : "");
        if (c.sameSamples && !skipping)
            EXPECT_EQ(inBricks, all) << what;
        else
            EXPECT_NEAR(inBricks, all, 0.06 * all) << what;
    }
}

const BrickCase kBrickCases[] = {
    {"slicer", "slicer", {{"offset", 12}}},
    {"slicer_gradient", "slicer", {{"offset", -20}, {"gradient", 1}}},
    {"mip", "mip", {}},
    {"mip_hardware_orthographic", "mip", {}, Interpolation::Hardware, false, false, Projection::Orthographic},
    {"minip", "minip", {}},
    {"average_nearest", "average", {}, Interpolation::Nearest},
    {"slab_mip", "slab_mip", {{"thickness", 40}}},
    {"firsthit", "firsthit", {{"threshold", 120}}},
    {"firsthit_depth_hardware", "firsthit", {{"threshold", 60}, {"depth", 1}}, Interpolation::Hardware},
    {"composite", "composite", {}, Interpolation::Trilinear, true, false, Projection::Perspective, false},
    {"composite_hardware_orthographic", "composite", {}, Interpolation::Hardware, true, false, Projection::Orthographic, false},
    {"composite_shaded_gradient_opacity", "composite", {{"shading", 1}, {"gradient_opacity", 1}}, Interpolation::Trilinear, true, false, Projection::Perspective, false},
    {"composite_back_to_front_jitter", "composite", {{"back_to_front", 1}, {"jitter", 1}}, Interpolation::Trilinear, true, false, Projection::Perspective, false},
    {"composite_preclassified_nearest", "composite", {{"preclassify", 1}}, Interpolation::Nearest, true, false, Projection::Perspective, false},
    {"composite_no_early_termination", "composite", {{"early_termination", 1.0}}, Interpolation::Trilinear, true, false, Projection::Perspective, false},
    {"iso", "iso", {{"isovalue", 100}}, Interpolation::Trilinear, false, false, Projection::Perspective, false},
    {"iso_depth_no_refinement", "iso", {{"isovalue", 60}, {"depth", 1}, {"refinement_steps", 0}}, Interpolation::Trilinear, false, false,
     Projection::Perspective, false},
    {"tf2d_shaded", "tf2d", {{"shading", 1}}, Interpolation::Trilinear, false, true,
     Projection::Perspective, false},
    // 26 neighbours of 8 voxels each per sample: 30 s on 2 cores, so labelled
    // heavy (tests/CMakeLists.txt); it reaches no further than central
    // differences, which the case above covers in the default run.
    {"tf2d_shaded_sobel", "tf2d", {{"shading", 1}, {"sobel", 1}}, Interpolation::Trilinear, false, true,
     Projection::Perspective, false},
};

INSTANTIATE_TEST_SUITE_P(Renderers, BrickedKeepsTheImage, ::testing::ValuesIn(kBrickCases),
                         [](const ::testing::TestParamInfo<BrickCase>& info) { return std::string(info.param.name); });

// Bricks that stay on the GPU (render/volume_textures.h), counted through
// the engine: the passes drawn and the bricks uploaded.
class BrickResidency : public GlTest {
protected:
    struct Frame {
        std::size_t drawn = 0, uploaded = 0;
        Image image;
    };
    Frame renderCounted(const Scene& scene) {
        const std::size_t drawn = engine().bricksDrawn(), uploads = engine().brickUploads();
        Frame f;
        f.image = asPng(engine().render(scene));
        f.drawn = engine().bricksDrawn() - drawn;
        f.uploaded = engine().brickUploads() - uploads;
        return f;
    }
    Image unbricked(Scene scene) {
        scene.gpuMemoryMiB.reset();
        return asPng(engine().render(scene));
    }
    static const Volume& bonsai() {
        static const Volume v = loadVolume(datasetPath("bonsai.nrrd"));
        return v;
    }
};

TEST_F(BrickResidency, ASettledCameraUploadsNothing) {
    // The isosurface at 200 (the pot) lies in a few of the 18 bricks: the
    // others are empty for it and are neither drawn nor uploaded, and the
    // ones drawn fit the pool, so the second frame of the same view
    // uploads nothing.
    engine().setVolume(bonsai());
    Scene scene = bonsaiScene({"iso", {{"isovalue", 200}}});
    scene.skipEmptySpace = true;
    scene.gpuMemoryMiB = 12.0;
    const Frame first = renderCounted(scene);
    const BrickLayout& l = engine().brickLayout();
    ASSERT_EQ(l.bricks.size(), 18u);
    ASSERT_GE(l.resident, 8u);
    EXPECT_GT(first.drawn, 0u);
    EXPECT_LT(first.drawn, l.bricks.size()) << "empty bricks are drawn";
    EXPECT_LE(first.drawn, l.resident);
    EXPECT_EQ(first.uploaded, first.drawn);
    const Frame second = renderCounted(scene);
    EXPECT_EQ(second.drawn, first.drawn);
    EXPECT_EQ(second.uploaded, 0u);
    EXPECT_LE(compareForGrading(unbricked(scene), second.image, Tolerance{}).maxDifference, 1.0);
}

TEST_F(BrickResidency, ATurningCameraUploadsOnlyWhatThePoolCannotHold) {
    // Compositing draws all 18 bricks, 11 fit: with the last frame's order
    // as the forecast a frame reuses at least 10 of the bricks it left
    // (plain least-recently-used eviction would reuse none: every brick
    // would be evicted just before the frame comes back to it).
    engine().setVolume(bonsai());
    Scene scene = bonsaiScene({"composite", {}, Interpolation::Trilinear, true});
    scene.gpuMemoryMiB = 12.0;
    renderCounted(scene);  // cold
    const std::size_t resident = engine().brickLayout().resident;
    ASSERT_EQ(resident, 11u);
    for (int f = 0; f < 4; ++f) {
        scene.camera.azimuth += 0.5;
        const Frame frame = renderCounted(scene);
        EXPECT_EQ(frame.drawn, 18u);
        EXPECT_LE(frame.uploaded, frame.drawn - resident + 1) << "frame " << f;
        if (f == 3) EXPECT_LE(compareForGrading(unbricked(scene), frame.image, Tolerance{}).maxDifference, 1.0);
    }
}

TEST_F(BrickResidency, BricksOutOfViewAreNeitherDrawnNorUploaded) {
    // Looked at along -y, orthographic, magnified 4 times: the image shows
    // the middle quarter of the 256-voxel box across x and z (voxels 96 to
    // 160), which lies inside the middle brick column's 86 to 172; only
    // that column's three bricks are drawn (MIP draws every brick it
    // sees: it skips no empty space).
    engine().setVolume(bonsai());
    Scene scene = bonsaiScene({"mip", {}, Interpolation::Trilinear, false, false, Projection::Orthographic});
    scene.camera.view = "-y";
    scene.camera.zoom = 4.0;
    scene.gpuMemoryMiB = 8.0;
    const Frame zoomed = renderCounted(scene);
    const BrickLayout& l = engine().brickLayout();
    ASSERT_EQ(l.bricks.size(), 27u);
    ASSERT_EQ(l.bricks[13].lo, glm::ivec3(86));  // the middle brick
    ASSERT_EQ(l.bricks[13].hi, glm::ivec3(172));
    EXPECT_EQ(zoomed.drawn, 3u);
    EXPECT_LE(zoomed.uploaded, zoomed.drawn);
    EXPECT_LE(compareForGrading(unbricked(scene), zoomed.image, Tolerance{}).maxDifference, 1.0);
}

// 2100 x 128 x 128: longer than llvmpipe's largest 3D texture (2048), so
// there is no unbricked image to compare with. The volume is f(x) only (a
// ramp with a bright band at x = 2060..2079, past the first 2048 voxels),
// seen orthographically along +y with nearest sampling: every sample of a
// pixel's ray has the value of the voxel column under it, so the MIP is
// f(column) and the first hit above 200 is the band. The column under a
// pixel comes from the camera's own ray (Camera::ray), the value from the
// voxels.
class LongVolume : public GlTest {};

TEST_F(LongVolume, MipAndFirstHitAgreeWithTheVoxelsBeyondTheTextureLimit) {
    const glm::ivec3 dims(2100, 128, 128);
    auto f = [](int x) { return x >= 2060 && x < 2080 ? 250 : (x * 199) / 2099; };
    std::vector<std::uint8_t> bytes(std::size_t(dims.x) * dims.y * dims.z);
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = std::uint8_t(f(int(i % std::size_t(dims.x))));
    const Volume v(dims, VoxelType::UInt8, glm::dvec3(1.0), std::move(bytes), "long");
    Scene scene;
    scene.renderer = "mip";
    scene.camera.view = "+y";
    scene.camera.projection = Projection::Orthographic;
    scene.width = 700;
    scene.height = 60;
    scene.interpolation = Interpolation::Nearest;
    scene.window = glm::dvec2(0.0, 255.0);
    const std::vector<int> mip = renderGrey(v, scene);
    ASSERT_TRUE(engine().brickLayout().bricked());
    EXPECT_GE(engine().brickLayout().count.x, 2);
    const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
    // The voxel column under pixel (x, y), where its ray crosses the box's
    // middle plane y = 64; -1 off the box or on a voxel face (either column).
    auto column = [&](int x, int y) {
        glm::dvec3 o, d;
        cam.ray(x + 0.5, y + 0.5, &o, &d);
        const glm::dvec3 p = o + (64.0 - o.y) / d.y * d;
        if (p.x < 0.5 || p.x > dims.x - 0.5 || p.z < 0.5 || p.z > dims.z - 0.5) return -1;
        if (std::abs(p.x - std::round(p.x)) < 0.05) return -1;
        return int(std::floor(p.x));
    };
    int compared = 0, band = 0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            if (column(x, y) < 0) continue;
            const int expected = f(column(x, y));
            ASSERT_LE(std::abs(mip[std::size_t(y) * scene.width + x] - expected), 1) << "pixel " << x << "," << y;
            ++compared;
            band += expected == 250;
        }
    EXPECT_GT(compared, 20000);
    EXPECT_GT(band, 200) << "the band beyond voxel 2048 was compared";
    scene.renderer = "firsthit";
    scene.parameters["threshold"] = 200.0;
    const std::vector<int> hit = renderGrey(v, scene);
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            if (column(x, y) < 0) continue;
            const int value = f(column(x, y));
            ASSERT_LE(std::abs(hit[std::size_t(y) * scene.width + x] - (value >= 200 ? value : 0)), 1)
                << "pixel " << x << "," << y;
        }
}

class BrickRefusals : public GlTest {};

std::string errorOf(const Volume& v, const Scene& scene) {
    try {
        GlTest::renderGrey(v, scene);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST_F(BrickRefusals, WhatNeedsTheWholeVolumeSaysSoInOneLine) {
    static const Volume v = loadVolume("phantom:sphere:96");  // 3.4 MiB of float32
    Scene scene;
    scene.width = scene.height = 32;
    scene.gpuMemoryMiB = 1.0;
    engine().setVolume(v);
    struct Refusal {
        const char* renderer;
        std::vector<std::pair<const char*, double>> parameters;
        const char* says;
        Interpolation interpolation = Interpolation::Trilinear;
        double step = 0.5;
    };
    const Refusal refusals[] = {
        {"texslice3d", {}, "texslice3d: draws the whole volume's slices and does not draw a bricked volume"},
        {"splat", {}, "splat: draws the whole volume's slices"},
        {"attenuated_mip", {}, "attenuated_mip: does not draw a bricked volume"},
        {"composite", {{"shadows", 1}}, "composite: parameter 'shadows' reads beyond one brick"},
        {"composite", {{"ambient_occlusion", 1}}, "composite: parameter 'ambient_occlusion' reads beyond one brick"},
        {"composite", {{"precomputed_gradients", 1}, {"shading", 1}}, "parameter 'precomputed_gradients' does not combine"},
        {"mip", {}, "mip: cubic interpolation does not combine with a bricked volume", Interpolation::CatmullRom},
        {"iso", {}, "iso: a step above 1", Interpolation::Trilinear, 2.0},
    };
    for (const Refusal& r : refusals) {
        scene.renderer = r.renderer;
        scene.parameters.clear();
        for (const auto& [name, value] : r.parameters) scene.parameters[name] = value;
        scene.interpolation = r.interpolation;
        scene.step = r.step;
        const std::string what = errorOf(v, scene);
        ASSERT_TRUE(engine().brickLayout().bricked());
        EXPECT_NE(what.find(r.says), std::string::npos) << r.renderer << ": " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_NE(what.find("bricks for a 1 MiB GPU memory budget"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace voxlab::testing
