// Shadows (the shadows stage, composite with `shadows` on), against the
// CPU's transmittance along light rays through an analytic phantom.
//
// The phantom "sphere-over-slab" at N = 64: an opaque slab (value 1) fills
// 6.4 <= z <= 16, a sphere of value 0.5 and radius R = 9.6 floats above it,
// centred at (32, 32, 38.4). The transfer function is white; the sphere's
// material has opacity alpha_s = 0.1 per unit length, the slab's 1. The
// camera looks straight down (-z view, orthographic); the light is tilted
// by 35 degrees from the view, so the sphere's shadow falls beside it on the
// slab. Shading is off: a sample's colour is white times the transmittance
// T read from the light volume.
//
// For a pixel whose ray misses the sphere and ends on the slab, the colour
// with shadows over the colour without is the transmittance at the slab's
// top, s = (x, y, 16), towards the light. The CPU computes it from the
// sphere's chord along the light ray (a line-sphere intersection):
//     T = (1 - alpha_s)^chord
// The slab's own samples, just under its top, see a little of the slab
// towards the light too; that factor is the same for every slab pixel, so
// the ratios are divided by their median over pixels whose light ray
// misses the sphere by 2 voxels or more (where T = 1).
//
// Tolerance, derived: the sphere's surface is voxelised (its value jumps
// from 0.5 to 0 between voxel centres and is interpolated across one
// voxel), and the shadow ray samples it every voxel (the light volume's
// texel is one voxel here), so the chord the shader sees can differ from the
// analytic one by up to 1 voxel at each end; the light volume is
// interpolated between texels one voxel apart, whose rays are shifted by
// tan(35) = 0.7 voxel. So within 2 voxels of chord: |T_image - T_cpu| <=
// T_cpu (1 - (1 - alpha_s)^2) + 2/255 (8-bit rounding of both images).
// Pixels within 2 voxels of the shadow's edge (light rays grazing the
// sphere) are left out, where the chord changes fastest.
//
// The shape: every pixel whose light ray passes through the sphere's core
// (2 voxels inside it) is darker than 0.9 of the lit slab, and every one
// whose light ray misses the sphere by 2 voxels is within 3% of it: the
// shadow is the sphere's projection along the light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/gl_fixture.h"
#include "voxlab/camera.h"
#include "voxlab/phantoms.h"
#include "voxlab/stage_registry.h"

namespace voxlab::testing {
namespace {

constexpr int kN = 64;
constexpr int kImage = 128;
constexpr double kSphereAlpha = 0.1;
constexpr double kLightAzimuth = 35.0;

TransferFunction whiteMaterials() {
    const glm::vec3 white(1.0f);
    return TransferFunction({{0.0, white, 0.0f},
                             {0.3, white, 0.0f},
                             {0.4, white, float(kSphereAlpha)},
                             {0.6, white, float(kSphereAlpha)},
                             {0.9, white, 1.0f},
                             {1.0, white, 1.0f}});
}

Scene shadowScene(bool shadows) {
    Scene scene;
    scene.renderer = "composite";
    scene.camera.view = "-z";
    scene.camera.projection = Projection::Orthographic;
    scene.width = scene.height = kImage;
    scene.step = 0.25;
    scene.interpolation = Interpolation::Hardware;
    scene.transferFunction = whiteMaterials();
    scene.parameters["shadows"] = shadows ? 1.0 : 0.0;
    scene.parameters["light_azimuth"] = kLightAzimuth;
    scene.parameters["light_elevation"] = 0.0;
    scene.parameters["early_termination"] = 1.0;
    return scene;
}

// The unit vector towards the light, by lighting.glsl's documented rule:
// the view direction reversed, turned by the azimuth towards the image's
// right and by the elevation towards its top.
glm::dvec3 towardsLight(const Camera& cam, double azimuth, double elevation) {
    const double az = glm::radians(azimuth), el = glm::radians(elevation);
    return glm::normalize(-cam.forward * (std::cos(az) * std::cos(el)) + cam.right * (std::sin(az) * std::cos(el)) -
                          cam.down * std::sin(el));
}

// Length of the ray s + t d (t >= 0) inside the sphere, and how far the
// ray's line passes from the centre.
double chord(glm::dvec3 s, glm::dvec3 d, double* miss) {
    const glm::dvec3 c = sphereOverSlabCentre(kN);
    const double r = sphereOverSlabRadius(kN);
    const double along = glm::dot(c - s, d);
    *miss = glm::length(c - s - along * d);
    if (*miss >= r || along <= 0.0) return 0.0;
    return 2.0 * std::sqrt(r * r - *miss * *miss);
}

class Shadows : public GlTest {};

TEST_F(Shadows, TheSphereShadowsTheSlabByTheTransmittanceAlongLightRays) {
    const Volume volume = makePhantom("phantom:sphere-over-slab:64");
    engine().setVolume(volume);
    const Image lit = engine().render(shadowScene(false));
    const Image shadowed = engine().render(shadowScene(true));
    const Camera cam = Camera::make(shadowScene(true).camera, volume.extent(), kImage, kImage);
    const glm::dvec3 light = towardsLight(cam, kLightAzimuth, 0.0);
    ASSERT_GT(light.z, 0.5) << "the light should come from above the slab (+z)";
    const double r = sphereOverSlabRadius(kN);
    const glm::dvec3 centre = sphereOverSlabCentre(kN);

    struct SlabPixel {
        double ratio, transmittance, miss;
    };
    std::vector<SlabPixel> pixels;
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) {
            glm::dvec3 origin, direction;
            cam.ray(x + 0.5, y + 0.5, &origin, &direction);
            const glm::dvec2 w(origin.x, origin.y);
            // On the slab, away from the box's sides, and not behind the sphere.
            if (glm::any(glm::lessThan(w, glm::dvec2(2.0))) || glm::any(glm::greaterThan(w, glm::dvec2(kN - 2.0))))
                continue;
            if (glm::length(w - glm::dvec2(centre)) < r + 2.0) continue;
            const double without = lit.at(x, y).r;
            if (without < 0.2) continue;
            double miss = 0.0;
            const double length = chord(glm::dvec3(w, 0.25 * kN), light, &miss);
            pixels.push_back({shadowed.at(x, y).r / without, std::pow(1.0 - kSphereAlpha, length), miss});
        }
    ASSERT_GT(pixels.size(), 2000u) << "the slab is not where the test expects it";
    std::vector<double> litRatios;
    for (const SlabPixel& p : pixels)
        if (p.miss > r + 2.0) litRatios.push_back(p.ratio);
    ASSERT_GT(litRatios.size(), 500u);
    std::nth_element(litRatios.begin(), litRatios.begin() + litRatios.size() / 2, litRatios.end());
    const double self = litRatios[litRatios.size() / 2];
    std::printf("slab's own shadow factor (median over lit pixels): %.4f\n", self);
    EXPECT_GT(self, 0.8) << "the slab shadows its own top: does the shadow ray start at the sample itself?";

    int core = 0, outside = 0, compared = 0;
    double worst = 0.0, sum = 0.0;
    for (const SlabPixel& p : pixels) {
        const double t = p.ratio / self;
        if (p.miss < r - 2.0) {
            ++core;
            EXPECT_LT(t, 0.9) << "a slab point whose light ray crosses the sphere's core is not in shadow";
        }
        if (p.miss > r + 2.0) {
            ++outside;
            EXPECT_NEAR(t, 1.0, 0.03) << "a slab point whose light ray misses the sphere is shadowed";
        }
        if (std::abs(p.miss - r) < 2.0) continue;
        const double bound = p.transmittance * (1.0 - std::pow(1.0 - kSphereAlpha, 2.0)) + 2.0 / 255.0;
        const double error = std::abs(t - p.transmittance);
        EXPECT_LE(error, bound) << "T = " << p.transmittance << ", miss " << p.miss;
        worst = std::max(worst, error / bound);
        sum += error;
        ++compared;
    }
    std::printf("%d slab pixels compared (%d in the shadow's core, %d lit): mean |T - T_cpu| %.4f, worst %.2f of "
                "the bound\n",
                compared, core, outside, sum / compared, worst);
    EXPECT_GT(core, 100) << "too few pixels in the shadow: is the light where the test expects it?";
}

// The light volume is made again when the light, the transfer function, its
// resolution or the volume changes: an engine that rendered something else in between
// gives the same image as before, and the same as a fresh engine.
TEST_F(Shadows, TheLightVolumeFollowsTheLightTheTransferFunctionItsResolutionAndTheVolume) {
    const Volume volume = makePhantom("phantom:sphere-over-slab:64");
    const Volume other = makePhantom("phantom:sphere-over-slab:48");
    const Scene scene = shadowScene(true);
    engine().setVolume(volume);
    const Image first = engine().render(scene);
    Scene turned = scene;
    turned.parameters["light_azimuth"] = -kLightAzimuth;
    const Image turnedImage = engine().render(turned);
    Scene dimmer = scene;
    dimmer.transferFunction = TransferFunction({{0.0, glm::vec3(1.0f), 0.0f}, {1.0, glm::vec3(1.0f), 0.05f}});
    engine().render(dimmer);
    Scene coarse = scene;
    coarse.parameters["shadow_resolution"] = 16.0;
    engine().render(coarse);
    engine().setVolume(other);
    engine().render(scene);
    engine().setVolume(volume);
    const Image again = engine().render(scene);
    double difference = 0.0, turnedDifference = 0.0;
    for (std::size_t i = 0; i < first.rgba.size(); ++i) {
        difference = std::max(difference, double(std::abs(first.rgba[i] - again.rgba[i])));
        turnedDifference = std::max(turnedDifference, double(std::abs(first.rgba[i] - turnedImage.rgba[i])));
    }
    EXPECT_EQ(difference, 0.0);
    EXPECT_GT(turnedDifference, 0.2) << "turning the light did not move the shadow";
    RenderEngine fresh(rendererRegistry());
    fresh.setVolume(volume);
    const Image freshTurned = fresh.render(turned);
    engine().setVolume(volume);
    const Image ours = engine().render(turned);
    for (std::size_t i = 0; i < ours.rgba.size(); ++i) ASSERT_EQ(ours.rgba[i], freshTurned.rgba[i]);
}

// One engine draws a pre-integrated scene (a 2D table) and then one with
// shadows (a 3D light volume) in the same slot: a texture name once bound as
// 2D cannot become 3D, so the engine must make a new one (it raised
// GL_INVALID_OPERATION once).
TEST_F(Shadows, AnEngineSwitchesBetweenPreintegrationAndShadows) {
    const Volume volume = makePhantom("phantom:sphere-over-slab:64");
    engine().setVolume(volume);
    Scene table = shadowScene(false);
    table.parameters["preintegrated"] = 1.0;
    EXPECT_NO_THROW(engine().render(table));
    const Image shadows = engine().render(shadowScene(true));
    EXPECT_NO_THROW(engine().render(table));
    RenderEngine fresh(rendererRegistry());
    fresh.setVolume(volume);
    const Image expected = fresh.render(shadowScene(true));
    for (std::size_t i = 0; i < expected.rgba.size(); ++i) ASSERT_EQ(shadows.rgba[i], expected.rgba[i]);
}

// Shadows only darken: with them, no pixel of a shaded bonsai is brighter.
TEST_F(Shadows, ShadowsOnlyDarken) {
    const Volume volume = loadVolume(datasetPath("bonsai.nrrd"));
    engine().setVolume(volume);
    Scene scene = Scene::load(std::string(VOXLAB_SOURCE_DIR) + "/reference/shadows/scenes/bonsai_side_light.json");
    scene.parameters["shadows"] = 0.0;
    const Image plain = engine().render(scene);
    scene.parameters["shadows"] = 1.0;
    const Image shadowed = engine().render(scene);
    double darker = 0.0;
    for (std::size_t i = 0; i < plain.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        ASSERT_LE(shadowed.rgba[i], plain.rgba[i] + 1e-5f);
        darker += plain.rgba[i] - shadowed.rgba[i];
    }
    EXPECT_GT(darker / (plain.rgba.size() * 0.75), 0.005) << "shadows changed nothing";
}

}  // namespace
}  // namespace voxlab::testing
