// Two volumes fused (scene "fusion", composite) and clip planes (scene
// "clip_planes"), against CPU compositing written here from scene.h's
// definitions (support/cpu_ray.h):
//  - the second volume covers the first's box; a sample at p reads it at
//    the same place in the box, voxel coordinate p / extent1 * dims2,
//    trilinearly (or the containing voxel, with nearest interpolation);
//  - each volume is classified by its own transfer function, and the two
//    are combined: checkerboard (cells of checker_size smallest spacings,
//    the first volume where the cell's index sum is even), split (the first
//    where dot(p - point, normal) >= 0), color_opacity (the second's colour,
//    the first's opacity) or sum (opacities added and clamped to 1, colour
//    their opacity-weighted mean);
//  - clip planes shorten each ray to the half-spaces they keep before the
//    samples are placed (t_entry moves), and every sample the CPU takes is
//    checked to lie in all of them.
// Tolerance: 2 grey levels per channel (tables baked to 0.5/255, float on
// the GPU). Pixels with a sample within 1e-3 voxel of a checker cell's or
// the split plane's border are left out and counted.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <random>

#include <nlohmann/json.hpp>

#include "support/cpu_ray.h"
#include "support/cpu_sampling.h"
#include "support/gl_fixture.h"
#include "voxlab/error.h"

namespace voxlab::testing {
namespace {

template <class F>
Volume floatVolume(glm::ivec3 d, glm::dvec3 spacing, F f) {
    std::vector<float> values;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i) values.push_back(float(f(i, j, k)));
    std::vector<std::uint8_t> bytes(values.size() * 4);
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return Volume(d, VoxelType::Float32, spacing, bytes, "test");
}

double cpuNearest(const Volume& v, glm::dvec3 p) {
    return clampedVoxel(v, glm::ivec3(glm::floor(p / v.spacing())));
}

std::vector<CameraSpec> cameras() {
    std::vector<CameraSpec> out;
    for (const char* view : {"+x", "-y", "+z"}) {
        CameraSpec c;
        c.view = view;
        c.projection = Projection::Orthographic;
        out.push_back(c);
    }
    CameraSpec orbit;
    orbit.azimuth = -28.0, orbit.elevation = 17.0;
    out.push_back(orbit);
    return out;
}

const std::vector<ControlPoint> kFirst = {{-40, glm::vec3(1.0f, 0.3f, 0.2f), 0.0f},
                                          {60, glm::vec3(1.0f, 0.9f, 0.3f), 0.35f}};
const std::vector<ControlPoint> kSecond = {{0, glm::vec3(0.1f, 0.4f, 1.0f), 0.3f},
                                           {10, glm::vec3(0.2f, 1.0f, 0.5f), 0.05f}};

class Fusion : public GlTest {
protected:
    // The first volume (anisotropic, signed values) and a coarser second one.
    Fusion()
        : first_(floatVolume({16, 12, 10}, {1.0, 1.5, 2.0}, [](int i, int j, int k) { return 10.0 * std::sin(0.7 * i + j) * k - 20; })),
          second_(floatVolume({7, 5, 4}, {3.0, 1.0, 1.0}, [](int i, int j, int k) { return double((i * 7 + j * 3 + k * 5) % 11); })) {
        second_ = Volume(second_.dims(), second_.type(), second_.spacing(), second_.bytes().copy(), "second");
        saveNrrd(second_, path_);
    }

    glm::dvec4 classify(glm::dvec3 p, const voxlab::Fusion& f, Interpolation interpolation, bool* ambiguous) const {
        const bool nearest = interpolation == Interpolation::Nearest;
        const glm::dvec3 p2 = p / first_.extent() * second_.extent();
        const glm::dvec4 a = cpuTransferFunction(kFirst, nearest ? cpuNearest(first_, p) : cpuTrilinear(first_, p));
        const glm::dvec4 b = cpuTransferFunction(kSecond, nearest ? cpuNearest(second_, p2) : cpuTrilinear(second_, p2));
        switch (f.mode) {
            case FusionMode::Checkerboard: {
                const glm::dvec3 u = p / (f.checkerSize * first_.minSpacing());
                for (int k = 0; k < 3; ++k)
                    if (std::abs(u[k] - std::round(u[k])) < 1e-3) *ambiguous = true;
                const glm::ivec3 cell(glm::floor(u));
                return ((cell.x + cell.y + cell.z) & 1) == 0 ? a : b;
            }
            case FusionMode::Split: {
                const glm::dvec3 point = *f.splitPoint * first_.spacing();
                const double s = glm::dot(p - point, glm::normalize(f.splitNormal));
                if (std::abs(s) < 1e-3) *ambiguous = true;
                return s >= 0.0 ? a : b;
            }
            case FusionMode::ColorOpacity: return {glm::dvec3(b), a.a};
            case FusionMode::Sum: {
                const double total = a.a + b.a;
                const glm::dvec3 c = total > 0.0 ? (a.a * glm::dvec3(a) + b.a * glm::dvec3(b)) / total : glm::dvec3(0.0);
                return {c, std::min(total, 1.0)};
            }
        }
        return glm::dvec4(0.0);
    }

    Volume first_, second_;
    std::string path_ = ::testing::TempDir() + "/voxlab_fusion_second_" + std::to_string(getpid()) + ".nrrd";
};

TEST_F(Fusion, EveryModeMatchesCpuCompositingOfTheTwoClassifications) {
    engine().setVolume(first_);
    for (FusionMode mode : {FusionMode::Checkerboard, FusionMode::Split, FusionMode::ColorOpacity, FusionMode::Sum})
        for (Interpolation interpolation : {Interpolation::Trilinear, Interpolation::Nearest})
            for (const CameraSpec& cam : cameras()) {
                voxlab::Fusion f;
                f.dataset = path_;
                f.mode = mode;
                f.transferFunction = TransferFunction(kSecond);
                f.checkerSize = 3.3;
                f.splitPoint = glm::dvec3(7.2, 5.1, 4.4);
                f.splitNormal = glm::dvec3(0.4, -1.0, 0.3);
                Scene scene;
                scene.renderer = "composite";
                scene.camera = cam;
                scene.width = scene.height = 40;
                scene.step = 0.5;
                scene.interpolation = interpolation;
                scene.transferFunction = TransferFunction(kFirst);
                scene.parameters = {{"early_termination", 1.0}};
                scene.fusion = f;
                const Image image = engine().render(scene);
                const Camera camera = Camera::make(cam, first_.extent(), 40, 40);
                double worst = 0.0;
                int ambiguousPixels = 0, visible = 0;
                for (int y = 0; y < 40; ++y)
                    for (int x = 0; x < 40; ++x) {
                        bool ambiguous = false;
                        glm::dvec3 o, d;
                        camera.ray(x + 0.5, y + 0.5, &o, &d);
                        const glm::dvec4 expected = cpuCompositeRay(
                            o, d, first_.extent(), {}, 0.5, 0.5, 1.0,
                            [&](glm::dvec3 p) { return classify(p, f, interpolation, &ambiguous); });
                        if (ambiguous) {
                            ++ambiguousPixels;
                            continue;
                        }
                        visible += expected.a > 0.05;
                        for (int ch = 0; ch < 3; ++ch)
                            worst = std::max(worst, 255.0 * std::abs(double(image.at(x, y)[ch]) - expected[ch]));
                    }
                const std::string what = std::string(fusionModeName(mode)) + " " + interpolationName(interpolation) +
                                         " " + (cam.view.empty() ? "orbit" : cam.view);
                std::printf("fusion %-32s worst %.2f levels (%d visible, %d ambiguous)\n", what.c_str(), worst,
                            visible, ambiguousPixels);
                EXPECT_LE(worst, 2.0) << what;
                EXPECT_GT(visible, 200) << what;
                EXPECT_LT(ambiguousPixels, 1600 / 10) << what;
            }
}

TEST_F(Fusion, ScenesCheckTheirKeysAndTheSecondVolumeIsRefusedWhereItCannotBeDrawn) {
    const auto parse = [](const std::string& text) {
        return Scene::fromJson(nlohmann::json::parse(text), "s.json", "");
    };
    const Scene s = parse(R"({"dataset": "phantom:sphere", "fusion": {"dataset": "phantom:shells", "mode": "split",
        "window": [0, 200], "checker_size": 4, "split": {"point": [1, 2, 3], "normal": [0, 1, 0]}},
        "clip_planes": [{"point": [1, 2, 3], "normal": [1, 0, 0]}]})");
    ASSERT_TRUE(s.fusion);
    EXPECT_EQ(s.fusion->mode, FusionMode::Split);
    EXPECT_EQ(s.clipPlanes.size(), 1u);
    EXPECT_EQ(Scene::fromJson(s.toJson(), "again", "").toJson(), s.toJson());
    const std::vector<std::pair<std::string, std::string>> bad = {
        {R"({"dataset": "phantom:sphere", "fusion": {"mode": "sum"}})", "fusion.dataset: missing"},
        {R"({"dataset": "phantom:sphere", "fusion": {"dataset": "phantom:shells", "mode": "average"}})", "unknown fusion mode 'average'"},
        {R"({"dataset": "phantom:sphere", "fusion": {"dataset": "phantom:shells", "checker_size": 0}})", "fusion.checker_size"},
        {R"({"dataset": "phantom:sphere", "fusion": {"dataset": "phantom:shells", "split": {"normal": [0, 0, 0]}}})", "fusion.split.normal: must not be zero"},
        {R"({"dataset": "phantom:sphere", "clip_planes": [{"point": [0, 0, 0]}]})", "clip_planes[0].normal: missing"},
        {R"({"dataset": "phantom:sphere", "clip_planes": [{"point": [0, 0, 0], "normal": [0, 0, 0]}]})", "clip_planes[0].normal: must not be zero"},
        {R"({"dataset": "phantom:sphere", "clip_planes": [{"point":[0,0,0],"normal":[1,0,0]},{"point":[0,0,0],"normal":[1,0,0]},{"point":[0,0,0],"normal":[1,0,0]},{"point":[0,0,0],"normal":[1,0,0]},{"point":[0,0,0],"normal":[1,0,0]},{"point":[0,0,0],"normal":[1,0,0]},{"point":[0,0,0],"normal":[1,0,0]}]})", "at most 6 planes"},
        {R"({"dataset": "phantom:sphere", "fusion": {"dataset": "phantom:shells"}, "labels": "phantom:nested-labels"})", ""},
    };
    for (const auto& [text, expected] : bad) {
        if (expected.empty()) continue;
        try {
            parse(text);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    }
    // Labels and fusion together, or fusion with a renderer that cannot draw it.
    engine().setVolume(first_);
    Scene both = parse(R"({"dataset": "phantom:sphere", "renderer": "composite", "size": [8, 8],
        "fusion": {"dataset": "phantom:shells:16"}, "labels": "phantom:nested-labels:16"})");
    EXPECT_THROW(engine().render(both), Error);
    Scene mip = parse(R"({"dataset": "phantom:sphere", "renderer": "mip", "size": [8, 8], "fusion": {"dataset": "phantom:shells:16"}})");
    try {
        engine().render(mip);
        ADD_FAILURE() << "mip drew a fused volume";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("mip: does not draw a fused second volume"), std::string::npos) << e.what();
    }
}

// Clip planes: MIP and composite of the sphere phantom with 1 to 6 random
// oblique planes, against the CPU's clipped rays.
class ClipPlanes : public GlTest {};

TEST_F(ClipPlanes, RaysAreClippedToEveryHalfSpaceAsTheCpuClipsThem) {
    const Volume volume = loadVolume("phantom:sphere:32");
    engine().setVolume(volume);
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    int totalSamples = 0;
    for (int planes = 1; planes <= 6; ++planes)
        for (const char* renderer : {"mip", "composite"}) {
            Scene scene;
            scene.renderer = renderer;
            scene.camera.azimuth = 40.0 * planes, scene.camera.elevation = 10.0 * planes - 25.0;
            scene.width = scene.height = 40;
            scene.step = 0.5;
            scene.interpolation = Interpolation::Trilinear;
            scene.window = glm::dvec2(0.0, 1.0);
            if (std::string(renderer) == "composite") {
                scene.transferFunction = TransferFunction({{0, glm::vec3(1.0f), 0.0f}, {1, glm::vec3(1.0f), 0.2f}});
                scene.parameters = {{"early_termination", 1.0}};
            }
            std::vector<HalfSpace> keep;
            for (int p = 0; p < planes; ++p) {
                // Planes 3 to 9 voxels from the centre, each keeping the
                // centre's side: together they cut a polytope out of the sphere.
                const glm::dvec3 normal(uni(rng), uni(rng), uni(rng));
                const glm::dvec3 point = glm::dvec3(16.0) - (6.0 + 3.0 * uni(rng)) * glm::normalize(normal);
                scene.clipPlanes.push_back({point, normal});
                keep.push_back({point * volume.spacing(), glm::normalize(normal)});
            }
            const Image image = engine().render(scene);
            const Camera cam = Camera::make(scene.camera, volume.extent(), 40, 40);
            double worst = 0.0;
            int lit = 0;
            for (int y = 0; y < 40; ++y)
                for (int x = 0; x < 40; ++x) {
                    glm::dvec3 o, d;
                    cam.ray(x + 0.5, y + 0.5, &o, &d);
                    double maximum = 0.0;
                    const glm::dvec4 c = cpuCompositeRay(o, d, volume.extent(), keep, 0.5, 0.5, 1.0, [&](glm::dvec3 p) {
                        for (const HalfSpace& h : keep) EXPECT_GE(glm::dot(p - h.point, h.normal), -1e-9);
                        ++totalSamples;
                        const double v = cpuTrilinear(volume, p);
                        maximum = std::max(maximum, v);
                        return glm::dvec4(1.0, 1.0, 1.0, 0.2 * v);
                    });
                    const double expected = std::string(renderer) == "mip" ? maximum : c.r;
                    lit += expected > 0.05;
                    worst = std::max(worst, 255.0 * std::abs(double(image.at(x, y).r) - expected));
                }
            std::printf("%d clip plane(s), %-9s worst %.2f levels, %d lit pixels\n", planes, renderer, worst, lit);
            EXPECT_LE(worst, 2.0) << planes << " planes, " << renderer;
            EXPECT_GT(lit, 40) << planes << " planes, " << renderer;
        }
    EXPECT_GT(totalSamples, 10000);
}

}  // namespace
}  // namespace voxlab::testing
