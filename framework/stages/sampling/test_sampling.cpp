// The "sampling" stage (reference/sampling/sampling.glsl): the value the
// renderers read between voxels. The slicer shows sample_volume() on a plane,
// so an orthographic slicer at a random orbit angle and offset gives, at every
// pixel, the GPU's value at a known world point: where that pixel's ray
// (Camera::make) meets the plane through the box centre moved by
// offset * smallest spacing along the view direction. Those values are
// checked against nearest and trilinear interpolation computed here in double
// precision from the README's conventions (voxel i covers [i, i+1], its centre
// at i + 1/2; indices clamped to the grid), on real datasets (8-bit, 16-bit,
// signed and anisotropic) and a float phantom.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <sstream>
#include <string>

#include "support/cpu_sampling.h"
#include "support/gl_fixture.h"
#include "voxlab/camera.h"

namespace voxlab::testing {
namespace {

// Continuous voxel coordinates of a world point: voxel i spans [i, i+1].
glm::dvec3 voxelCoordinates(const Volume& v, glm::dvec3 p) { return p / v.spacing(); }

// The voxel whose cell [i, i+1]^3 contains p.
double cpuNearest(const Volume& v, glm::dvec3 p) {
    const glm::ivec3 i(glm::floor(voxelCoordinates(v, p)));
    return clampedVoxel(v, i);
}

// Distance (in voxels) from p to the nearest cell boundary on any axis.
double distanceToCellBoundary(const Volume& v, glm::dvec3 p) {
    const glm::dvec3 u = voxelCoordinates(v, p);
    double d = 1.0;
    for (int a = 0; a < 3; ++a) d = std::min(d, std::abs(u[a] - std::round(u[a])));
    return d;
}

// Distance (in voxels) from p to the box's faces, negative outside.
double distanceInsideBox(const Volume& v, glm::dvec3 p) {
    const glm::dvec3 u = voxelCoordinates(v, p);
    double d = 1e300;
    for (int a = 0; a < 3; ++a) d = std::min({d, u[a], v.dims()[a] - u[a]});
    return d;
}

// A slicer scene at a random orthographic orbit and offset, with the window
// set to the data range so that grey r means the value lo + r (hi - lo).
Scene randomSlice(const Volume& v, std::mt19937& rng, Interpolation interpolation, int size) {
    std::uniform_real_distribution<double> azimuth(0.0, 360.0), elevation(-80.0, 80.0), unit(-1.0, 1.0);
    Scene scene;
    scene.renderer = "slicer";
    scene.camera.view = "";
    scene.camera.azimuth = azimuth(rng);
    scene.camera.elevation = elevation(rng);
    scene.camera.projection = Projection::Orthographic;
    scene.width = scene.height = size;
    scene.interpolation = interpolation;
    scene.window = glm::dvec2(v.minValue(), v.maxValue());
    // Up to a quarter of the smallest box side either way: the plane still
    // cuts the box in a large area.
    const glm::dvec3 ext = v.extent();
    const double reach = 0.25 * std::min({ext.x, ext.y, ext.z}) / v.minSpacing();
    scene.parameters["offset"] = reach * unit(rng);
    return scene;
}

// Where each pixel's ray meets the slicer's plane (world units); nullopt for
// rays parallel to it. The plane passes through the box centre moved by
// offset * smallest spacing along the camera's forward direction, which is
// its normal.
std::vector<std::optional<glm::dvec3>> slicePoints(const Volume& v, const Scene& scene) {
    const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
    const glm::dvec3 n = cam.forward;
    const glm::dvec3 c = 0.5 * v.extent() + scene.parameters.at("offset") * v.minSpacing() * n;
    std::vector<std::optional<glm::dvec3>> out;
    for (int py = 0; py < scene.height; ++py)
        for (int px = 0; px < scene.width; ++px) {
            glm::dvec3 o, d;
            cam.ray(px + 0.5, py + 0.5, &o, &d);
            const double denom = glm::dot(d, n);
            if (std::abs(denom) < 1e-9) {
                out.push_back(std::nullopt);
                continue;
            }
            out.push_back(o + glm::dot(c - o, n) / denom * d);
        }
    return out;
}

// The value a grey pixel stands for under the scene's window.
double valueOfGrey(const Scene& scene, float r) { return scene.window->x + r * (scene.window->y - scene.window->x); }

std::string describe(const Scene& scene) {
    std::ostringstream s;
    s << "azimuth " << scene.camera.azimuth << ", elevation " << scene.camera.elevation << ", offset "
      << scene.parameters.at("offset");
    return s.str();
}

// Counts how many in-box pixels of a random slice differ from `oracle` by
// more than `tolerance` (data units). Pixels whose point lies within
// `boundaryMargin` voxels of a cell boundary are skipped when the margin is
// positive (nearest: either neighbour may be right there); pixels within
// 1e-3 voxel of the box's faces are always skipped (inside or outside is a
// matter of float rounding there).
template <class Oracle>
void expectSliceMatches(const Volume& v, const Scene& scene, Oracle oracle, double tolerance,
                        double boundaryMargin, double* maxError) {
    GlTest::engine().setVolume(v);
    const Image img = GlTest::engine().render(scene);
    const auto points = slicePoints(v, scene);
    int checked = 0, bad = 0;
    std::string first;
    for (int py = 0; py < scene.height; ++py)
        for (int px = 0; px < scene.width; ++px) {
            const auto& p = points[std::size_t(py) * scene.width + px];
            if (!p || distanceInsideBox(v, *p) < 1e-3) continue;
            if (boundaryMargin > 0.0 && distanceToCellBoundary(v, *p) < boundaryMargin) continue;
            const double got = valueOfGrey(scene, img.at(px, py).r);
            const double want = oracle(v, *p);
            const double err = std::abs(got - want);
            *maxError = std::max(*maxError, err);
            ++checked;
            if (err > tolerance && bad++ == 0) {
                std::ostringstream s;
                s << "pixel (" << px << ", " << py << ") at voxel coordinates (" << p->x / v.spacing().x << ", "
                  << p->y / v.spacing().y << ", " << p->z / v.spacing().z << "): GPU " << got << ", CPU " << want;
                first = s.str();
            }
        }
    // The plane must really cross the box over a good part of the image.
    EXPECT_GT(checked, scene.width * scene.height / 8) << describe(scene);
    EXPECT_EQ(bad, 0) << describe(scene) << ": " << bad << " of " << checked << " pixels off; first: " << first;
}

// A seed that depends on the test volume only (FNV-1a), so every run and
// every standard library draws the same engine state.
std::uint32_t seedFor(const std::string& name) {
    std::uint32_t h = 2166136261u;
    for (char c : name) h = (h ^ std::uint8_t(c)) * 16777619u;
    return h;
}

// Real datasets of every storage type, and a float phantom.
class Sampling : public GlTest, public ::testing::WithParamInterface<std::string> {};

constexpr int kSize = 64;   // pixels per side of each slice image
constexpr int kAngles = 6;  // random orbits per volume and interpolation

TEST_P(Sampling, TrilinearEqualsCpuTrilinearAtRandomPoints) {
    const Volume v = namedVolume(GetParam());
    const double range = v.maxValue() - v.minValue();
    // Tolerance 1/255 of the value range (one grey level). The explicit
    // trilinear stage is float arithmetic on exact voxel values; the only
    // other error is the float position of the sample (about 1e-4 voxel for
    // these box sizes). Measured on llvmpipe: at most 0.004 grey level.
    const double tolerance = range / 255.0;
    std::mt19937 rng(seedFor(GetParam()));
    double maxError = 0.0;
    for (int a = 0; a < kAngles; ++a) {
        const Scene scene = randomSlice(v, rng, Interpolation::Trilinear, kSize);
        expectSliceMatches(v, scene, cpuTrilinear, tolerance, 0.0, &maxError);
    }
    RecordProperty("max_error_in_grey_levels", std::to_string(maxError / range * 255.0));
}

TEST_P(Sampling, NearestEqualsTheVoxelThatContainsThePoint) {
    const Volume v = namedVolume(GetParam());
    const double range = v.maxValue() - v.minValue();
    // A voxel value comes back exactly up to float rounding of the texel and
    // the window (about 1e-6 of the range); 1e-3 of the range (a quarter of
    // a grey level) leaves a wide margin and still tells neighbours apart
    // whenever they differ by a visible amount. Points within 1e-3 voxel of a
    // cell boundary are skipped: float positions (error ~1e-4 voxel) may land
    // on either side.
    const double tolerance = 1e-3 * range;
    std::mt19937 rng(seedFor(GetParam()));
    double maxError = 0.0;
    for (int a = 0; a < kAngles; ++a) {
        const Scene scene = randomSlice(v, rng, Interpolation::Nearest, kSize);
        expectSliceMatches(v, scene, cpuNearest, tolerance, 1e-3, &maxError);
    }
}

// The GPU's own filtering (GL_LINEAR) and the explicit stage must agree.
// Hardware filtering is allowed to be coarse: many GPUs keep 8 bits of each
// weight (up to 1/512 of the neighbours' difference per axis, 1.5 grey levels
// over three axes in the worst case) and some filter 8-bit textures in 8-bit
// fixed point (the result rounded to a texel step, one more level). The bound
// is 3 grey levels, of the value range or, for 8-bit data, of the 8-bit
// texel range. Measured on llvmpipe over 40 random slices per volume: up to
// 1.36 texel steps on the uint8 volumes (8-bit fixed-point filtering) and
// below 0.001 grey level on the 16-bit and float ones.
TEST_P(Sampling, HardwareFilteringAgreesWithExplicitTrilinear) {
    const Volume v = namedVolume(GetParam());
    const double range = v.maxValue() - v.minValue();
    const double scale = v.type() == VoxelType::UInt8 ? std::max(range, 255.0) : range;
    const double tolerance = 3.0 * scale / 255.0;
    std::mt19937 rng(seedFor(GetParam()) + 1);
    double maxError = 0.0;
    for (int a = 0; a < kAngles; ++a) {
        Scene scene = randomSlice(v, rng, Interpolation::Trilinear, kSize);
        engine().setVolume(v);
        const Image explicitImg = engine().render(scene);
        scene.interpolation = Interpolation::Hardware;
        const Image hardwareImg = engine().render(scene);
        const auto points = slicePoints(v, scene);
        int bad = 0, checked = 0;
        for (int py = 0; py < scene.height; ++py)
            for (int px = 0; px < scene.width; ++px) {
                const auto& p = points[std::size_t(py) * scene.width + px];
                if (!p || distanceInsideBox(v, *p) < 1e-3) continue;
                const double err = std::abs(valueOfGrey(scene, explicitImg.at(px, py).r) -
                                            valueOfGrey(scene, hardwareImg.at(px, py).r));
                maxError = std::max(maxError, err);
                ++checked;
                bad += err > tolerance;
            }
        EXPECT_GT(checked, scene.width * scene.height / 8) << describe(scene);
        EXPECT_EQ(bad, 0) << describe(scene) << ": " << bad << " of " << checked << " pixels differ by more than "
                          << tolerance;
    }
    RecordProperty("max_difference_in_grey_levels", std::to_string(maxError / range * 255.0));
}

INSTANTIATE_TEST_SUITE_P(RealAndPhantomVolumes, Sampling,
                         ::testing::Values(std::string("fuel.nrrd"),     // uint8, 64^3
                                           std::string("tooth.nrrd"),    // uint8, non-cubic
                                           std::string("cthead.nrrd"),   // uint16, spacing 1 1 2
                                           std::string("headsq.nrrd"),   // int16, spacing 3.2 3.2 1.5
                                           std::string("phantom:marschner-lobb:41")),  // float32
                         [](const auto& info) {
                             std::string s = info.param.substr(0, info.param.find('.'));
                             for (char& c : s)
                                 if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                             return s;
                         });

// Clamp-to-edge: past the outermost voxel centres trilinear interpolation
// holds the border value. A ramp along x read on a plane x = const inside the
// outermost half voxel shows that border voxel's value, not an extrapolation
// or a blend with a wrapped-around voxel.
TEST_F(GlTest, TrilinearHoldsTheBorderValueOutsideTheOutermostCentres) {
    const Volume v = makePhantom("phantom:ramp-x:16");  // value = i + 1/2
    for (const char* view : {"+x", "-x"}) {
        for (double x : {0.2, 15.8}) {
            SCOPED_TRACE(std::string(view) + ", plane x = " + std::to_string(x));
            Scene scene;
            scene.renderer = "slicer";
            scene.camera.view = view;
            scene.camera.projection = Projection::Orthographic;
            scene.width = scene.height = 16;
            scene.interpolation = Interpolation::Trilinear;
            // A window wider than the data, so that an extrapolated value
            // beyond the border would show instead of being clamped away.
            scene.window = glm::dvec2(-4.0, 20.0);
            scene.parameters["offset"] = (view[0] == '+' ? 1.0 : -1.0) * (x - 8.0);
            engine().setVolume(v);
            const Image img = engine().render(scene);
            const double want = x < 8 ? 0.5 : 15.5;
            for (int py = 0; py < 16; ++py)
                for (int px = 0; px < 16; ++px)
                    ASSERT_NEAR(valueOfGrey(scene, img.at(px, py).r), want, 1e-3) << px << "," << py;
        }
    }
}

}  // namespace
}  // namespace voxlab::testing
