// The ray profile (RenderEngine::profileRay), taken from the renderers' own
// shaders in an instrumented run, held to oracles that do not come from
// those shaders:
//  - the renderer's image: a profile's last pixel, laid over the
//    background, is the pixel the renderer drew (for every ray-casting
//    renderer, on a grid of pixels of small oblique renders, with jitter,
//    early termination, a slab, a cutting plane);
//  - the data: along +z through one voxel column, orthographic, nearest,
//    sample k is voxel k and the running maximum is the maximum so far;
//  - the transfer function on the CPU (support/cpu_tf.h): the opacity the
//    compositing stage applied to each sample is the function's at the
//    sample's value, corrected for the step;
//  - a planted bug: a copy of the reference whose mip.glsl takes every
//    other sample shows, in the profile, the maximum of the even samples,
//    where the reference shows the maximum of all;
//  - the starter code: a stage whose stub is reached says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include "support/cpu_tf.h"
#include "support/gl_fixture.h"
#include "support/temp_dir.h"
#include "voxlab/error.h"
#include "voxlab/project_root.h"
#include "voxlab/ray_profile.h"
#include "voxlab/stage_registry.h"

namespace voxlab::testing {
namespace {

// Per channel: the profile reads the same shader's pixels back, so the
// difference is float rounding (the cut ray's last sample count and the
// whole ray's agree) and, for back-to-front compositing, the order of the
// sums; 1.5 of 255 covers llvmpipe's and a GPU's.
constexpr double kPixelTolerance = 1.5 / 255.0;

const Volume& dataset(const std::string& name) {
    static std::map<std::string, Volume> cache;
    auto it = cache.find(name);
    if (it == cache.end()) it = cache.emplace(name, loadVolume(datasetPath(name))).first;
    return it->second;
}

TransferFunction preset(const std::string& name) { return TransferFunction::load(datasetPath("tf/" + name)); }

Scene orbitScene(const std::string& renderer, int size, double azimuth, double elevation) {
    Scene s;
    s.renderer = renderer;
    s.width = s.height = size;
    s.camera.azimuth = azimuth;
    s.camera.elevation = elevation;
    s.step = 0.5;
    s.interpolation = Interpolation::Trilinear;
    s.background = glm::vec3(0.1f, 0.2f, 0.3f);
    return s;
}

class RayProfileTest : public GlTest {};

// ---------------------------------------------------------------------------
// The profile's last pixel is the renderer's.

struct PixelCase {
    const char* name;
    const char* dataset;
    Scene scene;
};

std::vector<PixelCase> pixelCases() {
    std::vector<PixelCase> cases;
    Scene composite = orbitScene("composite", 40, 30, 20);
    composite.transferFunction = preset("bonsai.json");
    std::vector<ControlPoint> dense = composite.transferFunction->points();
    for (ControlPoint& p : dense) p.alpha = std::min(1.0f, p.alpha * 4.0f);  // rays that stop early
    composite.transferFunction = TransferFunction(dense);
    cases.push_back({"composite_early_termination", "bonsai.nrrd", composite});
    Scene shaded = composite;
    shaded.parameters = {{"shading", 1}, {"jitter", 1}};
    cases.push_back({"composite_shaded_jitter", "bonsai.nrrd", shaded});
    Scene backToFront = composite;
    backToFront.parameters = {{"back_to_front", 1}};
    cases.push_back({"composite_back_to_front", "bonsai.nrrd", backToFront});
    Scene cut = composite;
    cut.cuttingPlane = CuttingPlane{};
    cut.cuttingPlane->normal = glm::dvec3(1.0, 0.3, 0.0);
    cases.push_back({"composite_cutting_plane", "bonsai.nrrd", cut});
    for (const char* r : {"mip", "minip", "average"}) cases.push_back({r, "tooth.nrrd", orbitScene(r, 40, 40, 15)});
    Scene slab = orbitScene("slab_mip", 40, 40, 15);
    slab.parameters = {{"thickness", 30}, {"offset", 10}};
    cases.push_back({"slab_mip", "tooth.nrrd", slab});
    Scene firsthit = orbitScene("firsthit", 40, 30, 20);
    firsthit.parameters = {{"threshold", 120}};
    cases.push_back({"firsthit", "bonsai.nrrd", firsthit});
    Scene iso = orbitScene("iso", 40, 30, 20);
    iso.parameters = {{"isovalue", 100}};
    cases.push_back({"iso", "tooth.nrrd", iso});
    Scene tf2d = orbitScene("tf2d", 40, 30, 20);
    tf2d.transferFunction2D = TransferFunction2D::load(datasetPath("tf2d/bonsai.json"));
    cases.push_back({"tf2d", "bonsai.nrrd", tf2d});
    return cases;
}

TEST_F(RayProfileTest, TheLastPixelOfEveryProfileIsTheRenderersPixel) {
    for (const PixelCase& c : pixelCases()) {
        engine().setVolume(dataset(c.dataset));
        const Image image = engine().render(c.scene);
        double worst = 0.0;
        int hits = 0, stopped = 0, pixels = 0;
        for (int y = 2; y < c.scene.height; y += 6)
            for (int x = 2; x < c.scene.width; x += 6) {
                const RayProfile p = engine().profileRay(c.scene, x, y);
                ++pixels, hits += p.hitsVolume, stopped += p.stoppedAt >= 0;
                const glm::vec3 shown = profilePixel(p, c.scene.background);
                for (int k = 0; k < 3; ++k) worst = std::max(worst, double(std::abs(shown[k] - image.at(x, y)[k])));
                if (p.hitsVolume && !p.samples.empty())  // the last sample's pixel is the whole ray's
                    EXPECT_LE(glm::length(p.samples.back().accumulated - p.result), 1e-4f) << c.name;
            }
        std::printf("  %s: %d pixels, %d hit, %d stopped early; largest difference %.3f/255\n", c.name, pixels, hits,
                    stopped, worst * 255.0);
        EXPECT_GT(hits, pixels / 4) << c.name;
        EXPECT_LE(worst, kPixelTolerance) << c.name;
        if (std::string(c.name) == "composite_early_termination") EXPECT_GT(stopped, 2);
    }
    // The profile's draws leave the engine's image alone.
    const PixelCase last = pixelCases().back();
    engine().setVolume(dataset(last.dataset));
    const Image before = engine().render(last.scene);
    engine().profileRay(last.scene, 20, 20);
    EXPECT_EQ(engine().readBack().rgba, before.rgba);
}

// ---------------------------------------------------------------------------
// The samples are the data's.

Scene columnScene() {
    Scene s;
    s.renderer = "mip";
    s.camera.view = "+z";
    s.camera.projection = Projection::Orthographic;
    s.width = 103, s.height = 94;  // one pixel per voxel column of tooth (103 x 94 x 161)
    s.step = 1.0;
    s.interpolation = Interpolation::Nearest;
    return s;
}

TEST_F(RayProfileTest, AlongAVoxelColumnTheSamplesAreItsVoxels) {
    const Volume& volume = dataset("tooth.nrrd");
    engine().setVolume(volume);
    const RayProfile p = engine().profileRay(columnScene(), 40, 50);
    ASSERT_EQ(p.samples.size(), 161u) << p.why;
    EXPECT_NEAR(p.tEntry + 0.5, p.samples[0].t, 1e-4);
    double maximum = -1.0;
    for (int k = 0; k < 161; ++k) {
        // (Read as a normalised texel times 255: within a float's rounding.)
        EXPECT_NEAR(p.samples[k].value, volume.value(40, 50, k), 1e-3) << "sample " << k;
        EXPECT_NEAR(p.samples[k].position.z, k + 0.5, 1e-3);
        maximum = std::max(maximum, volume.value(40, 50, k));
        EXPECT_NEAR(p.samples[k].runningMax, maximum, 1e-3) << "sample " << k;
    }
    ASSERT_GE(p.chosen, 0);
    EXPECT_NEAR(p.samples[p.chosen].value, maximum, 1e-3);
}

// ---------------------------------------------------------------------------
// The student's code, bugs included.

TEST_F(RayProfileTest, APlantedBugInMipShowsInTheProfile) {
    // mip.glsl with every other sample skipped: an easy slip (m += 2) that
    // the image hides where the maximum is broad.
    TempDir root("voxlab-profile");
    std::ifstream in(projectRoot() + "/reference/mip/mip.glsl");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string loop = "for (int m = 0; m < n; ++m)";
    ASSERT_NE(text.find(loop), std::string::npos) << "the reference's loop changed: update the planted bug";
    text.replace(text.find(loop), loop.size(), "for (int m = 0; m < n; m += 2)");
    std::filesystem::create_directories(root.path() / "mip");
    std::ofstream(root.path() / "mip" / "mip.glsl") << text;

    const Volume& volume = dataset("tooth.nrrd");
    RenderEngine buggy(rendererRegistry(), root.path().string());
    buggy.setVolume(volume);
    const RayProfile p = buggy.profileRay(columnScene(), 40, 50);
    ASSERT_EQ(p.samples.size(), 161u) << p.why;
    double all = -1.0, even = -1.0;
    int differ = 0;
    for (int k = 0; k < 161; ++k) {
        all = std::max(all, volume.value(40, 50, k));
        if (k % 2 == 0) even = std::max(even, volume.value(40, 50, k));
        EXPECT_NEAR(p.samples[k].runningMax, even, 1e-3) << "sample " << k << ": the buggy loop's maximum";
        differ += std::abs(p.samples[k].runningMax - all) > 0.5;
    }
    EXPECT_GT(differ, 0) << "the planted bug should change the running maximum along this column";
}

TEST_F(RayProfileTest, AStageNotImplementedSaysSo) {
    RenderEngine starter(rendererRegistry(), projectRoot() + "/assignments");
    starter.setVolume(dataset("tooth.nrrd"));
    const RayProfile p = starter.profileRay(columnScene(), 40, 50);
    EXPECT_NE(p.why.find("not implemented"), std::string::npos) << p.why;
}

// ---------------------------------------------------------------------------
// What compositing applied, sample by sample.

TEST_F(RayProfileTest, CompositingAppliedTheTransferFunctionsOpacityCorrectedForTheStep) {
    const Volume& volume = dataset("bonsai.nrrd");
    Scene s = orbitScene("composite", 32, 30, 20);
    s.transferFunction = preset("bonsai.json");
    s.step = 0.7;
    engine().setVolume(volume);
    const RayProfile p = engine().profileRay(s, 12, 8);  // a ray through the pot
    ASSERT_TRUE(p.hitsVolume);
    int compared = 0;
    const std::size_t end = p.stoppedAt >= 0 ? std::size_t(p.stoppedAt) + 1 : p.samples.size();
    for (std::size_t i = 0; i < end; ++i) {
        const double before = i ? p.samples[i - 1].accumulated.a : 0.0;
        if (before > 0.9) break;  // the opacity is then a difference of nearly equal numbers
        const double a = cpuTransferFunction(s.transferFunction->points(), p.samples[i].value).a;
        const double corrected = 1.0 - std::pow(1.0 - a, s.step);
        EXPECT_NEAR(p.samples[i].classified.a, corrected, 2e-3) << "sample " << i << ", value " << p.samples[i].value;
        compared += corrected > 0.0;
    }
    EXPECT_GT(compared, 5) << "the ray should cross visible material";
}

// ---------------------------------------------------------------------------
// Why a ray stopped.

TEST_F(RayProfileTest, SaysWhyARayTerminatesEarly) {
    Scene s = orbitScene("composite", 32, 30, 20);
    s.transferFunction = TransferFunction({{30.0, glm::vec3(1.0f), 0.0f}, {60.0, glm::vec3(1.0f, 0.5f, 0.2f), 1.0f}});
    engine().setVolume(dataset("bonsai.nrrd"));
    const RayProfile p = engine().profileRay(s, 12, 8);  // a ray through the pot
    ASSERT_TRUE(p.hitsVolume);
    ASSERT_GE(p.stoppedAt, 1) << p.why;
    EXPECT_EQ(p.why.rfind("early ray termination: accumulated opacity ", 0), 0u) << p.why;
    EXPECT_NE(p.why.find(">= 0.99"), std::string::npos) << p.why;
    EXPECT_GE(p.samples[p.stoppedAt].accumulated.a, 0.99f);
    EXPECT_LT(p.samples[p.stoppedAt - 1].accumulated.a, 0.99f);
    EXPECT_LT(p.stoppedAt + 1, int(p.samples.size())) << "the ray should have had samples left";

    s.parameters["back_to_front"] = 1;  // composites everything, and says so
    const RayProfile all = engine().profileRay(s, 12, 8);
    EXPECT_EQ(all.stoppedAt, -1);
    EXPECT_EQ(all.why, "the ray left the volume");
}

TEST_F(RayProfileTest, SaysWhenARayMissesTheVolume) {
    Scene s = orbitScene("composite", 32, 30, 20);
    engine().setVolume(dataset("tooth.nrrd"));
    // The perspective orbit fits the bounding sphere: the corner's ray misses the box.
    const RayProfile p = engine().profileRay(s, 0, 0);
    EXPECT_FALSE(p.hitsVolume);
    EXPECT_TRUE(p.samples.empty());
    EXPECT_EQ(p.why, "the ray misses the volume");
    EXPECT_EQ(profilePixel(p, s.background), s.background);
    s.roi = RegionOfInterest{glm::dvec3(500.0), glm::dvec3(600.0)};  // outside the box: every ray
    EXPECT_FALSE(engine().profileRay(s, 16, 16).hitsVolume);
}

TEST_F(RayProfileTest, SaysWhereTheFirstHitAndTheSurfaceAre) {
    Scene s = orbitScene("firsthit", 32, 30, 20);
    s.parameters["threshold"] = 150;
    engine().setVolume(dataset("bonsai.nrrd"));
    const RayProfile p = engine().profileRay(s, 12, 8);  // a ray through the pot
    ASSERT_GE(p.stoppedAt, 0) << p.why;
    EXPECT_GE(p.samples[p.stoppedAt].value, 150.0);
    for (int m = 0; m < p.stoppedAt; ++m) EXPECT_LT(p.samples[m].value, 150.0) << "sample " << m;
    EXPECT_EQ(p.chosen, p.stoppedAt);

    s.renderer = "iso";
    s.parameters = {{"isovalue", 150}};
    engine().setVolume(dataset("tooth.nrrd"));
    const RayProfile iso = engine().profileRay(s, 16, 16);
    ASSERT_GE(iso.stoppedAt, 1) << iso.why;
    EXPECT_NE(iso.samples[iso.stoppedAt - 1].value >= 150.0, iso.samples[iso.stoppedAt].value >= 150.0)
        << "the surface lies between the stop and the sample before it";
    for (int m = 1; m < iso.stoppedAt; ++m)
        EXPECT_EQ(iso.samples[m - 1].value >= 150.0, iso.samples[m].value >= 150.0) << "an earlier crossing at " << m;
}

TEST_F(RayProfileTest, SlicesHaveNoRayAndPixelsOutsideTheImageAreAnError) {
    engine().setVolume(dataset("tooth.nrrd"));
    const RayProfile p = engine().profileRay(orbitScene("texslice3d", 32, 30, 20), 16, 16);
    EXPECT_TRUE(p.samples.empty());
    EXPECT_NE(p.why.find("draws slices"), std::string::npos) << p.why;
    try {
        engine().profileRay(orbitScene("mip", 32, 30, 20), 32, 0);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "ray profile: pixel (32, 0) is outside the 32x32 image");
    }
}

}  // namespace
}  // namespace voxlab::testing
