// The ray-profile inspector (computeRayProfile) against the GPU renderers:
// an independent implementation of the same conventions. For a grid of
// pixels of small oblique renders of real datasets, the profile's result laid
// over the background must be the pixel the renderer drew.
//
// Tolerance kPixelTolerance (1.5/255 per channel; llvmpipe agrees within
// 0.02/255 on every scene here): the GPU classifies through a float table
// that bake() sizes so that its linear interpolation stays within 0.5/255 of
// the exact piecewise-linear function the profile evaluates, and it computes
// ray set-up, sample positions and interpolation weights in float where the
// profile uses double; a float rounding can also move the early-termination
// test to the next sample or the sample count floor(L/step + 1/2) by one.
// A profile whose samples sit half a step off (t_entry + m step) misses by
// 2.8/255 on the first composite scene and far more on the others.
// Each comparison also prints the largest difference it measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "support/gl_fixture.h"
#include "voxlab/error.h"
#include "voxlab/ray_profile.h"

namespace voxlab::testing {
namespace {

constexpr double kPixelTolerance = 1.5 / 255.0;

const Volume& dataset(const std::string& name) {
    static std::map<std::string, Volume> cache;
    auto it = cache.find(name);
    if (it == cache.end()) it = cache.emplace(name, loadVolume(datasetPath(name))).first;
    return it->second;
}

TransferFunction preset(const std::string& name) { return TransferFunction::load(datasetPath("tf/" + name)); }

Scene orbitScene(const std::string& renderer, int size, double azimuth, double elevation,
                 Projection projection = Projection::Perspective) {
    Scene s;
    s.renderer = renderer;
    s.width = s.height = size;
    s.camera.view = "";
    s.camera.azimuth = azimuth;
    s.camera.elevation = elevation;
    s.camera.projection = projection;
    s.step = 0.5;
    s.interpolation = Interpolation::Trilinear;
    return s;
}

struct Comparison {
    double maxError = 0.0;
    int worstX = -1, worstY = -1;
    int pixels = 0, hits = 0, stopped = 0;
    std::vector<double> errors;  // per compared pixel, the largest over its channels
    // The share of pixels whose error exceeds `bound`.
    double shareOver(double bound) const {
        return double(std::count_if(errors.begin(), errors.end(), [&](double e) { return e > bound; })) /
               double(std::max<std::size_t>(errors.size(), 1));
    }
};

// Renders `scene` on the GPU and compares every `stride`-th pixel with the
// profile of its ray.
Comparison compareWithRenderer(const Volume& volume, const Scene& scene, int stride = 3,
                               const Scene* profileScene = nullptr) {
    GlTest::engine().setVolume(volume);
    const Image image = GlTest::engine().render(scene);
    Comparison c;
    for (int y = 1; y < scene.height; y += stride)
        for (int x = 1; x < scene.width; x += stride) {
            const RayProfile p = computeRayProfile(volume, profileScene ? *profileScene : scene, x, y);
            const glm::vec3 cpu = profilePixel(p, scene.background);
            const glm::vec4 gpu = image.at(x, y);
            double pixelError = 0.0;
            for (int k = 0; k < 3; ++k) {
                const double e = std::abs(double(cpu[k]) - double(gpu[k]));
                pixelError = std::max(pixelError, e);
                if (e > c.maxError) c.maxError = e, c.worstX = x, c.worstY = y;
            }
            c.errors.push_back(pixelError);
            ++c.pixels;
            c.hits += p.hitsVolume;
            c.stopped += p.stoppedAt >= 0;
        }
    std::printf("  %s: %d pixels (%d hit, %d stopped early), largest difference %.2f/255 at (%d, %d)\n",
                scene.renderer.c_str(), c.pixels, c.hits, c.stopped, c.maxError * 255.0, c.worstX, c.worstY);
    return c;
}

class RayProfileTest : public GlTest {};

// ---------------------------------------------------------------------------
// The profile's result is the renderer's pixel.

TEST_F(RayProfileTest, CompositeBonsaiWithEarlyTerminationMatchesTheRenderer) {
    Scene s = orbitScene("composite", 48, 30, 20);
    s.transferFunction = preset("bonsai.json");
    // A denser copy of the preset so that many rays reach the default 0.99.
    std::vector<ControlPoint> points = s.transferFunction->points();
    for (ControlPoint& p : points) p.alpha = std::min(1.0f, p.alpha * 4.0f);
    s.transferFunction = TransferFunction(points);
    const Comparison c = compareWithRenderer(dataset("bonsai.nrrd"), s);
    EXPECT_GT(c.hits, c.pixels / 3);
    EXPECT_GT(c.stopped, 10) << "the scene should exercise early termination";
    EXPECT_LE(c.maxError, kPixelTolerance) << "worst pixel (" << c.worstX << ", " << c.worstY << ")";
}

TEST_F(RayProfileTest, CompositeToothWithoutEarlyTerminationMatchesTheRenderer) {
    Scene s = orbitScene("composite", 48, 215, -155, Projection::Orthographic);
    s.transferFunction = preset("tooth.json");
    s.parameters["early_termination"] = 1.0;
    s.step = 1.0;
    s.background = glm::vec3(0.2f, 0.3f, 0.5f);
    const Comparison c = compareWithRenderer(dataset("tooth.nrrd"), s);
    EXPECT_GT(c.hits, c.pixels / 3);
    EXPECT_EQ(c.stopped, 0);
    EXPECT_LE(c.maxError, kPixelTolerance) << "worst pixel (" << c.worstX << ", " << c.worstY << ")";
}

// Shading (gradients, Phong), pre-classification, jitter and the fallback
// ramp (no transfer function) are modelled too.
TEST_F(RayProfileTest, CompositeShadedPreclassifiedJitteredMatchesTheRenderer) {
    Scene s = orbitScene("composite", 40, 120, 35);
    s.transferFunction = preset("tooth.json");
    s.parameters = {{"shading", 1}, {"preclassify", 1}, {"jitter", 1}, {"light_azimuth", 30}};
    const Comparison shaded = compareWithRenderer(dataset("tooth.nrrd"), s, 3);
    EXPECT_LE(shaded.maxError, kPixelTolerance) << "worst pixel (" << shaded.worstX << ", " << shaded.worstY << ")";

    Scene ramp = orbitScene("composite", 32, -40, 10);
    ramp.window = glm::dvec2(60.0, 255.0);
    const Comparison fallback = compareWithRenderer(dataset("bonsai.nrrd"), ramp, 3);
    EXPECT_LE(fallback.maxError, kPixelTolerance) << "worst pixel (" << fallback.worstX << ", " << fallback.worstY
                                                  << ")";
}

// Gradient-opacity modulation (the gradient_opacity stage) weights each
// sample's opacity by a ramp of |grad f|; with the ramp off the same pixels
// differ by far more than the tolerance, so the profile must model it.
TEST_F(RayProfileTest, CompositeWithGradientOpacityMatchesTheRenderer) {
    Scene s = orbitScene("composite", 40, 30, 20);
    s.transferFunction = preset("bonsai.json");
    s.parameters = {{"gradient_opacity", 1}, {"gradient_low", 4}, {"gradient_high", 30}};
    const Comparison c = compareWithRenderer(dataset("bonsai.nrrd"), s, 3);
    EXPECT_GT(c.hits, c.pixels / 3);
    EXPECT_LE(c.maxError, kPixelTolerance) << "worst pixel (" << c.worstX << ", " << c.worstY << ")";
    Scene plain = s;
    plain.parameters = {};
    EXPECT_GT(compareWithRenderer(dataset("bonsai.nrrd"), s, 3, &plain).maxError, 10 * kPixelTolerance);
}

// Local ambient occlusion (the ambient_occlusion stage) darkens each sample's
// colour by the opacity around it; the profile models it too.
TEST_F(RayProfileTest, CompositeWithAmbientOcclusionMatchesTheRenderer) {
    Scene s = orbitScene("composite", 40, 40, 25);
    s.transferFunction = preset("tooth.json");
    s.parameters = {{"ambient_occlusion", 1}, {"ao_radius", 6}, {"ao_strength", 1}, {"shading", 1}};
    const Comparison c = compareWithRenderer(dataset("tooth.nrrd"), s, 3);
    EXPECT_GT(c.hits, c.pixels / 4);
    EXPECT_LE(c.maxError, kPixelTolerance) << "worst pixel (" << c.worstX << ", " << c.worstY << ")";
    Scene plain = s;
    plain.parameters = {{"shading", 1}};
    EXPECT_GT(compareWithRenderer(dataset("tooth.nrrd"), s, 3, &plain).maxError, 10 * kPixelTolerance);
}

// A label map (the labels stage) and a fused second volume replace the
// classification; the profile classifies as their handout and scene.h say.
TEST_F(RayProfileTest, CompositeWithLabelsAndFusionMatchesTheRenderer) {
    for (const char* name : {"tooth_masks.json", "headsq_hu_anisotropic.json"}) {
        Scene s = Scene::load(std::string(VOXLAB_SOURCE_DIR) + "/reference/labels/scenes/" + name);
        s.width = s.height = 40;
        const Volume volume = loadVolume(s.dataset);
        const Comparison c = compareWithRenderer(volume, s, 3);
        EXPECT_GT(c.hits, c.pixels / 4) << name;
        EXPECT_LE(c.maxError, kPixelTolerance) << name << ": worst pixel (" << c.worstX << ", " << c.worstY << ")";
        Scene unlabelled = s;
        unlabelled.labels.reset();
        EXPECT_GT(compareWithRenderer(volume, s, 3, &unlabelled).maxError, 10 * kPixelTolerance) << name;
    }
    Scene fused = orbitScene("composite", 40, 30, 20);
    fused.transferFunction = preset("tooth.json");
    fused.fusion = Fusion{"phantom:shells:48", FusionMode::Checkerboard, std::nullopt,
                          TransferFunction({{0, glm::vec3(0.2f, 0.5f, 1.0f), 0.0f}, {80, glm::vec3(0.2f, 0.5f, 1.0f), 0.3f}}),
                          10.0, std::nullopt, glm::dvec3(1.0, 0.0, 0.0)};
    const Volume tooth = dataset("tooth.nrrd");
    for (FusionMode mode : {FusionMode::Checkerboard, FusionMode::Sum}) {
        fused.fusion->mode = mode;
        const Comparison c = compareWithRenderer(tooth, fused, 3);
        EXPECT_LE(c.maxError, kPixelTolerance) << fusionModeName(mode);
    }
}

// Pre-integration (the preintegration stage): each sample stands for the
// segment to the next one. The profile integrates each segment itself, in
// double; the GPU interpolates a 256x256 table whose texels are one value
// apart on 8-bit data, so a segment's colour and opacity differ by the
// table's bilinear error on the thin peaks (measured: under 1 grey level
// here): the tolerance is 2 levels, and post-classification of the same
// rays misses it by far more.
TEST_F(RayProfileTest, CompositePreintegratedFollowsTheRenderer) {
    Scene s = Scene::load(std::string(VOXLAB_SOURCE_DIR) + "/reference/preintegration/scenes/bonsai_thin_peaks.json");
    s.width = s.height = 40;
    s.interpolation = Interpolation::Trilinear;
    const Comparison c = compareWithRenderer(dataset("bonsai.nrrd"), s, 3);
    EXPECT_GT(c.hits, c.pixels / 4);
    EXPECT_LE(c.maxError, 2.0 / 255.0) << "worst pixel (" << c.worstX << ", " << c.worstY << ")";
    Scene post = s;
    post.parameters["preintegrated"] = 0.0;
    EXPECT_GT(compareWithRenderer(dataset("bonsai.nrrd"), s, 3, &post).maxError, 20 * 2.0 / 255.0);
}

// Shadows (the shadows stage): the profile follows each sample's shadow ray
// itself; the GPU reads a light volume of such rays from voxel centres,
// interpolated. Where the transmittance jumps within one light-volume voxel
// (the top of the opaque slab, the rim of a shadow) the two differ by up to
// that jump, tens of grey levels, so the bound is on the share of pixels:
// at most 2% of them off by more than 8 levels (measured: 0.8%). Without
// shadows, the shadow's pixels are (6%: it covers a small part of the view).
TEST_F(RayProfileTest, CompositeWithShadowsFollowsTheRenderer) {
    Scene s = Scene::load(std::string(VOXLAB_SOURCE_DIR) + "/reference/shadows/scenes/sphere_over_slab.json");
    s.width = s.height = 40;
    s.interpolation = Interpolation::Trilinear;
    const Volume phantom = loadVolume("phantom:sphere-over-slab:64");
    const Comparison c = compareWithRenderer(phantom, s, 2);
    EXPECT_GT(c.hits, c.pixels / 4);
    std::printf("  %.1f%% of the pixels off by more than 8 levels\n", 100.0 * c.shareOver(8.0 / 255.0));
    EXPECT_LE(c.shareOver(8.0 / 255.0), 0.02);
    Scene lit = s;
    lit.parameters["shadows"] = 0.0;
    const double unshadowed = compareWithRenderer(phantom, s, 2, &lit).shareOver(8.0 / 255.0);
    std::printf("  without shadows: %.1f%% of the pixels off by more than 8 levels\n", 100.0 * unshadowed);
    EXPECT_GT(unshadowed, 0.04);
}

TEST_F(RayProfileTest, ProjectionsMatchTheRenderer) {
    Scene mip = orbitScene("mip", 40, 60, -25, Projection::Orthographic);
    mip.window = glm::dvec2(20.0, 220.0);
    EXPECT_LE(compareWithRenderer(dataset("bonsai.nrrd"), mip).maxError, kPixelTolerance);

    // MinIP inside a region of interest (outside air would make it black).
    Scene minip = orbitScene("minip", 40, 200, 30);
    minip.roi = RegionOfInterest{glm::dvec3(20, 20, 30), glm::dvec3(80, 75, 130)};
    EXPECT_LE(compareWithRenderer(dataset("tooth.nrrd"), minip).maxError, kPixelTolerance);

    // The average through a transfer function, over a coloured background.
    Scene average = orbitScene("average", 40, 300, 15);
    average.transferFunction = preset("tooth.json");
    average.background = glm::vec3(0.1f, 0.4f, 0.2f);
    EXPECT_LE(compareWithRenderer(dataset("tooth.nrrd"), average).maxError, kPixelTolerance);
}

TEST_F(RayProfileTest, FirstHitAndIsoMatchTheRenderer) {
    Scene first = orbitScene("firsthit", 40, 30, 20);
    first.parameters["threshold"] = 120;
    first.window = glm::dvec2(0.0, 255.0);
    const Comparison c = compareWithRenderer(dataset("bonsai.nrrd"), first);
    EXPECT_GT(c.stopped, 10);
    EXPECT_LE(c.maxError, kPixelTolerance);

    Scene depth = first;
    depth.parameters["depth"] = 1;
    depth.interpolation = Interpolation::Nearest;
    EXPECT_LE(compareWithRenderer(dataset("bonsai.nrrd"), depth).maxError, kPixelTolerance);

    // The isosurface, refined and shaded.
    Scene iso = orbitScene("iso", 40, 150, -30);
    iso.parameters["isovalue"] = 180;
    EXPECT_LE(compareWithRenderer(dataset("tooth.nrrd"), iso).maxError, kPixelTolerance);
}

// The comparison notices samples half a step off: profiles whose rays start
// at a random offset in [-1/2, 1/2) of a step (jitter) against a render
// without it must differ beyond the tolerance somewhere.
TEST_F(RayProfileTest, TheComparisonNoticesSamplesMovedAlongTheRay) {
    Scene s = orbitScene("composite", 32, 30, 20);
    s.step = 1.0;
    std::vector<ControlPoint> points = preset("bonsai.json").points();
    for (ControlPoint& p : points) p.alpha = std::min(1.0f, p.alpha * 4.0f);
    s.transferFunction = TransferFunction(points);
    Scene jittered = s;
    jittered.parameters["jitter"] = 1;
    EXPECT_GT(compareWithRenderer(dataset("bonsai.nrrd"), s, 2, &jittered).maxError, kPixelTolerance);
}

// ---------------------------------------------------------------------------
// Why a ray stopped.

TEST_F(RayProfileTest, SaysWhyARayTerminatesEarly) {
    const Volume& volume = dataset("bonsai.nrrd");
    Scene s = orbitScene("composite", 32, 30, 20);
    s.transferFunction = TransferFunction({{30.0, glm::vec3(1.0f), 0.0f}, {60.0, glm::vec3(1.0f, 0.5f, 0.2f), 1.0f}});
    const RayProfile p = computeRayProfile(volume, s, 12, 8);  // a ray through the pot
    ASSERT_TRUE(p.hitsVolume);
    ASSERT_GE(p.stoppedAt, 1);
    EXPECT_EQ(p.why.rfind("early ray termination: accumulated opacity ", 0), 0u) << p.why;
    EXPECT_NE(p.why.find(">= 0.99"), std::string::npos) << p.why;
    EXPECT_GE(p.samples[p.stoppedAt].accumulated.a, 0.99f);
    EXPECT_LT(p.samples[p.stoppedAt - 1].accumulated.a, 0.99f);
    EXPECT_LT(p.stoppedAt + 1, int(p.samples.size())) << "the ray should have had samples left";
    EXPECT_FLOAT_EQ(p.result.a, p.samples[p.stoppedAt].accumulated.a);

    // Back to front composites everything, and says so.
    s.parameters["back_to_front"] = 1;
    const RayProfile all = computeRayProfile(volume, s, 12, 8);
    EXPECT_EQ(all.stoppedAt, -1);
    EXPECT_EQ(all.why.rfind("the ray left the volume", 0), 0u) << all.why;
}

TEST_F(RayProfileTest, SaysWhenARayMissesTheVolume) {
    Scene s = orbitScene("composite", 32, 30, 20);
    s.background = glm::vec3(0.25f, 0.5f, 0.75f);
    // The perspective orbit fits the bounding sphere: the corner's ray misses the box.
    const RayProfile p = computeRayProfile(dataset("tooth.nrrd"), s, 0, 0);
    EXPECT_FALSE(p.hitsVolume);
    EXPECT_TRUE(p.samples.empty());
    EXPECT_EQ(p.why, "the ray misses the volume");
    EXPECT_EQ(profilePixel(p, s.background), s.background);

    // So does every ray when the region of interest lies outside the box.
    s.roi = RegionOfInterest{glm::dvec3(500.0), glm::dvec3(600.0)};
    EXPECT_FALSE(computeRayProfile(dataset("tooth.nrrd"), s, 16, 16).hitsVolume);
}

TEST_F(RayProfileTest, SaysWhereTheFirstHitIs) {
    Scene s = orbitScene("firsthit", 32, 30, 20);
    s.parameters["threshold"] = 150;
    const RayProfile p = computeRayProfile(dataset("bonsai.nrrd"), s, 12, 8);  // a ray through the pot
    ASSERT_GE(p.stoppedAt, 0) << p.why;
    const double hit = p.samples[p.stoppedAt].value;
    EXPECT_GE(hit, 150.0);
    for (int m = 0; m < p.stoppedAt; ++m) EXPECT_LT(p.samples[m].value, 150.0) << "sample " << m;
    char expected[96];
    std::snprintf(expected, sizeof expected, "first hit: value %g >= threshold 150", hit);
    EXPECT_EQ(p.why, expected);
    EXPECT_EQ(p.chosen, p.stoppedAt);
}

TEST_F(RayProfileTest, SaysBetweenWhichSamplesTheIsovalueIsCrossed) {
    Scene s = orbitScene("iso", 32, 30, 20);
    s.parameters["isovalue"] = 150;
    const RayProfile p = computeRayProfile(dataset("tooth.nrrd"), s, 16, 16);
    ASSERT_GE(p.stoppedAt, 1) << p.why;
    EXPECT_EQ(p.why, "isovalue crossed between samples " + std::to_string(p.stoppedAt - 1) + " and " +
                         std::to_string(p.stoppedAt));
    EXPECT_NE(p.samples[p.stoppedAt - 1].value >= 150.0, p.samples[p.stoppedAt].value >= 150.0);
    EXPECT_GE(p.hitT, p.samples[p.stoppedAt - 1].t);
    EXPECT_LE(p.hitT, p.samples[p.stoppedAt].t);
}

// ---------------------------------------------------------------------------
// The samples themselves, and what is not modelled.

TEST_F(RayProfileTest, SamplesSitHalfAStepApartFromTheEntry) {
    const Volume& volume = dataset("tooth.nrrd");
    Scene s;
    s.renderer = "mip";
    s.camera.view = "+z";
    s.camera.projection = Projection::Orthographic;
    s.width = 103, s.height = 94;  // one pixel per voxel column
    s.step = 1.0;
    s.interpolation = Interpolation::Nearest;
    const RayProfile p = computeRayProfile(volume, s, 40, 50);
    ASSERT_EQ(p.samples.size(), 161u);
    EXPECT_NEAR(p.tEntry + 0.5, p.samples[0].t, 1e-9);
    double maximum = -1.0;
    for (int k = 0; k < 161; ++k) {
        // Sample k of a +z ray through a voxel column is voxel (40, 50, k).
        EXPECT_EQ(p.samples[k].value, volume.value(40, 50, k)) << "sample " << k;
        EXPECT_NEAR(p.samples[k].position.z, k + 0.5, 1e-9);
        maximum = std::max(maximum, p.samples[k].value);
        EXPECT_EQ(p.samples[k].runningMax, maximum);
    }
    EXPECT_EQ(p.samples[p.chosen].value, maximum);
}

TEST_F(RayProfileTest, OtherRenderersGiveValuesOnly) {
    Scene s = orbitScene("slicer", 32, 30, 20);
    const RayProfile p = computeRayProfile(dataset("tooth.nrrd"), s, 16, 16);
    EXPECT_TRUE(p.hitsVolume);
    EXPECT_FALSE(p.modelled);
    EXPECT_FALSE(p.samples.empty());
    EXPECT_EQ(p.why, "not modelled for slicer");
    EXPECT_THROW(computeRayProfile(dataset("tooth.nrrd"), s, 32, 0), Error);
}

}  // namespace
}  // namespace voxlab::testing
