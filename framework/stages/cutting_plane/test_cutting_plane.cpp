// Cropping: the region of interest (scene.roi) and the cutting plane
// (scene.cuttingPlane, stage reference/cutting_plane/cutting_plane.glsl).
//
//  - A MIP with a region of interest must equal the CPU maximum over the
//    voxels of that sub-box (axis views, nearest, step 1, box faces on voxel
//    boundaries); pixels outside the box's projection show the background.
//  - An axis-aligned cutting plane on a voxel boundary keeps a half-space
//    that a region of interest can also describe: with the other side "none",
//    the cut render must equal the same renderer cropped to that half; with
//    two renderers, each part of a view parallel to the plane must equal its
//    renderer cropped to its half; looking through the plane with opaque
//    grey output, the image must equal the front half alone.
//  - The command line's --cut-* options.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "support/axis_columns.h"
#include "support/gl_fixture.h"
#include "support/run_command.h"
#include "voxlab/camera.h"

namespace voxlab::testing {
namespace {

const AxisView& axisView(const std::string& name) {
    for (const AxisView& v : kAxisViews)
        if (name == v.name) return v;
    throw std::runtime_error("no axis view " + name);
}

// The in-plane voxel indices (along image right and image down) under the
// centre of pixel (px, py) of an axis view that fits the box into the image
// (README: uniform scale, centred). False outside the box or on a voxel
// boundary.
bool pixelVoxel(const Volume& v, const AxisView& view, int width, int height, int px, int py, int* ir, int* id) {
    const glm::dvec3 ext = v.extent();
    const double worldPerPixel = std::max(ext[view.rightAxis] / width, ext[view.downAxis] / height);
    const double r = (px + 0.5 - width / 2.0) * worldPerPixel;
    const double d = (py + 0.5 - height / 2.0) * worldPerPixel;
    const std::vector<int> irs = voxelCandidates(v, view.rightAxis, ext[view.rightAxis] / 2 + view.rightSign * r);
    const std::vector<int> ids = voxelCandidates(v, view.downAxis, ext[view.downAxis] / 2 + view.downSign * d);
    if (irs.size() != 1 || ids.size() != 1) return false;
    *ir = irs[0], *id = ids[0];
    return true;
}

// The CPU MIP of the sub-box roi (voxel coordinates, integers) for one pixel:
// nullopt when its ray misses the sub-box. The ray is clipped to the sub-box
// and sampled afresh from there: sample m at (m + 1/2) step past the entry
// face, floor(length / step + 1/2) samples, nearest voxel.
std::optional<double> cpuRoiMip(const Volume& v, const AxisView& view, const RegionOfInterest& roi, int ir, int id) {
    const int f = view.fwdAxis;
    if (ir < roi.min[view.rightAxis] || ir >= roi.max[view.rightAxis]) return std::nullopt;
    if (id < roi.min[view.downAxis] || id >= roi.max[view.downAxis]) return std::nullopt;
    const double s = v.spacing()[f], step = v.minSpacing();  // scene step 1
    // The sub-box along the view, as world distances from the box's front face.
    const int n = v.dims()[f];
    const double a = (view.fwdSign > 0 ? roi.min[f] : n - roi.max[f]) * s;
    const double b = (view.fwdSign > 0 ? roi.max[f] : n - roi.min[f]) * s;
    const int count = int(std::floor((b - a) / step + 0.5));
    if (count < 1) return std::nullopt;
    double best = -1e300;
    for (int m = 0; m < count; ++m) {
        const double depth = a + (m + 0.5) * step;  // from the front face
        const int k = std::clamp(int(std::floor(depth / s)), 0, n - 1);
        glm::ivec3 ijk;
        ijk[view.rightAxis] = ir;
        ijk[view.downAxis] = id;
        ijk[f] = view.fwdSign > 0 ? k : n - 1 - k;
        best = std::max(best, v.value(ijk.x, ijk.y, ijk.z));
    }
    return best;
}

// Pixel-by-pixel comparison of two images (rgb), over the pixels `use` picks.
template <class Use>
void expectSameImage(const Image& got, const Image& want, double tolerance, Use use, const std::string& what) {
    ASSERT_EQ(got.width, want.width);
    ASSERT_EQ(got.height, want.height);
    int bad = 0, compared = 0;
    std::string first;
    for (int y = 0; y < got.height; ++y)
        for (int x = 0; x < got.width; ++x) {
            if (!use(x, y)) continue;
            ++compared;
            const glm::vec4 a = got.at(x, y), b = want.at(x, y);
            const double err = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
            if (err > tolerance && bad++ == 0) {
                std::ostringstream s;
                s << "pixel (" << x << ", " << y << "): got (" << a.r << ", " << a.g << ", " << a.b << "), want ("
                  << b.r << ", " << b.g << ", " << b.b << ")";
                first = s.str();
            }
        }
    EXPECT_GT(compared, 0) << what;
    EXPECT_EQ(bad, 0) << what << ": " << bad << " of " << compared << " pixels differ; first " << first;
}

// Two renders of the same samples (only the clipping differs) agree to float
// rounding: the entry distance is computed by another formula (error ~1e-5
// world units), which with nearest sampling at voxel centres picks the same
// voxels. 1e-3 (a quarter of a grey level) is a wide margin that still sees
// any sample more or less.
constexpr double kSameRenderTolerance = 1e-3;

// Whether two images differ somewhere by more than a grey level (so that a
// comparison between them means something).
bool imagesDiffer(const Image& a, const Image& b) {
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        if (std::abs(a.rgba[i] - b.rgba[i]) > 2.0 / 255.0) return true;
    return false;
}

Image render(const Volume& v, const Scene& scene) {
    GlTest::engine().setVolume(v);
    return GlTest::engine().render(scene);
}

// --- region of interest ------------------------------------------------------

class RoiMip : public GlTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(RoiMip, EqualsTheCpuMipOverTheSubBox) {
    const Volume v = GetParam().rfind("phantom:", 0) == 0 ? makePhantom(GetParam())
                                                          : loadVolume(datasetPath(GetParam()));
    const glm::ivec3 d = v.dims();
    // Integer voxel bounds, off-centre on every axis.
    RegionOfInterest roi{glm::dvec3(glm::ivec3(d.x / 5, d.y / 4, d.z / 3)),
                         glm::dvec3(glm::ivec3(d.x * 3 / 4, d.y * 4 / 5, d.z * 5 / 6))};
    const glm::dvec2 window(v.minValue(), v.maxValue());
    const glm::vec3 background(0.2f, 0.3f, 0.4f);
    for (const AxisView& view : kAxisViews) {
        SCOPED_TRACE(std::string("view ") + view.name);
        Scene scene = axisViewScene(v, view, "mip");
        scene.roi = roi;
        scene.background = background;
        const Image img = render(v, scene);
        int bad = 0, inside = 0, outside = 0;
        std::string first;
        for (int py = 0; py < scene.height; ++py)
            for (int px = 0; px < scene.width; ++px) {
                int ir, id;
                if (!pixelVoxel(v, view, scene.width, scene.height, px, py, &ir, &id)) continue;
                const std::optional<double> m = cpuRoiMip(v, view, roi, ir, id);
                const glm::dvec3 want =
                    m ? glm::dvec3(std::clamp((*m - window.x) / (window.y - window.x), 0.0, 1.0))
                      : glm::dvec3(background);
                ++(m ? inside : outside);
                const glm::vec4 got = img.at(px, py);
                // One grey level: exact voxel values through float arithmetic.
                const double err = std::max({std::abs(got.r - want.r), std::abs(got.g - want.g),
                                             std::abs(got.b - want.b)});
                if (err > 1.0 / 255.0 && bad++ == 0) {
                    std::ostringstream s;
                    s << "pixel (" << px << ", " << py << "), voxel " << ir << ", " << id << ": got " << got.r
                      << ", want " << want.r << (m ? "" : " (background)");
                    first = s.str();
                }
            }
        EXPECT_EQ(bad, 0) << bad << " pixels off; first " << first;
        EXPECT_GT(inside, 0);
        EXPECT_GT(outside, 0);
    }
}

INSTANTIATE_TEST_SUITE_P(Volumes, RoiMip,
                         ::testing::Values(std::string("tooth.nrrd"),   // uint8, non-cubic
                                           std::string("headsq.nrrd"),  // int16, spacing 3.2 3.2 1.5
                                           std::string("phantom:marschner-lobb:32")),  // float32
                         [](const auto& info) {
                             std::string s = info.param.substr(0, info.param.find('.'));
                             for (char& c : s)
                                 if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                             return s;
                         });

// A region of interest that lies wholly outside the box keeps nothing: every
// pixel shows the background, in every axis view.
TEST_F(GlTest, RegionOfInterestOutsideTheBoxIsEmpty) {
    const Volume v = makePhantom("phantom:sphere:16");
    const glm::vec3 background(0.2f, 0.3f, 0.4f);
    for (const AxisView& view : kAxisViews) {
        for (const RegionOfInterest& roi : {RegionOfInterest{{-10.0, 0.0, 0.0}, {-5.0, 16.0, 16.0}},
                                            RegionOfInterest{{0.0, 0.0, 20.0}, {16.0, 16.0, 30.0}}}) {
            SCOPED_TRACE(std::string("view ") + view.name + ", roi x " + std::to_string(roi.min.x) + ".." +
                         std::to_string(roi.max.x) + ", z " + std::to_string(roi.min.z) + ".." +
                         std::to_string(roi.max.z));
            Scene scene = axisViewScene(v, view, "mip");
            scene.roi = roi;
            scene.background = background;
            const Image img = render(v, scene);
            int shown = 0;
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x) shown += img.at(x, y).r != background.r;
            EXPECT_EQ(shown, 0) << "pixels that show something; pixel (8, 8) is " << img.at(8, 8).r;
        }
    }
}

// --- cutting plane, one side -------------------------------------------------

// A renderer set-up to draw one side of a cut with.
struct Look {
    std::string renderer;
    std::optional<TransferFunction> tf;
    ParameterValues parameters;
};

// A colour ramp over the volume's value range [lo, hi], transparent at the
// low end.
TransferFunction greenish(const Volume& v) {
    const double lo = v.minValue(), hi = v.maxValue();
    return TransferFunction({{lo + 0.1 * (hi - lo), {0.0f, 0.2f, 0.1f}, 0.0f},
                             {lo + 0.35 * (hi - lo), {0.2f, 1.0f, 0.4f}, 0.03f},
                             {hi, {1.0f, 1.0f, 0.6f}, 0.2f}});
}

std::vector<Look> looks(const Volume& v) {
    const double midway = std::floor((v.minValue() + v.maxValue()) / 2.0) + 0.5;  // no voxel equals it
    return {{"mip", std::nullopt, {}},
            {"minip", greenish(v), {}},
            {"average", std::nullopt, {}},
            {"composite", greenish(v), {{"shading", 0.0}}},
            {"firsthit", std::nullopt, {{"threshold", midway}, {"depth", 1.0}}},
            {"slicer", std::nullopt, {}}};
}

// The inside of the CT head (uint16, spacing 1 1 2; 96 x 80 x 50 voxels):
// no air around it, so that every renderer (MinIP too) sees structure on
// both sides of a plane, and an even width puts the default plane (the
// centre, x = 48) on a voxel boundary.
Volume headInside() {
    const Volume v = loadVolume(datasetPath("cthead.nrrd"));
    const glm::ivec3 lo(80, 70, 30), d(96, 80, 50);
    std::vector<std::uint8_t> bytes(std::size_t(d.x) * d.y * d.z * 2);
    const auto* src = static_cast<const std::uint8_t*>(v.data());
    std::size_t o = 0;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i, o += 2) {
                const std::size_t index =
                    (lo.x + i) + std::size_t(v.dims().x) * ((lo.y + j) + std::size_t(v.dims().y) * (lo.z + k));
                std::memcpy(&bytes[o], src + index * 2, 2);
            }
    return Volume(d, v.type(), v.spacing(), bytes, "cthead-inside");
}

Scene lookScene(const Volume& v, const std::string& view, const Look& look) {
    Scene scene = axisViewScene(v, axisView(view), look.renderer.c_str());
    scene.transferFunction = look.tf;
    scene.parameters = look.parameters;
    scene.background = glm::vec3(0.2f, 0.3f, 0.4f);
    return scene;
}

// The half of the box on one side of the plane x = px (voxel coordinates):
// the side the normal (+1 or -1 along x) points into.
RegionOfInterest halfBox(const Volume& v, double px, int sign) {
    RegionOfInterest roi{glm::dvec3(0.0), glm::dvec3(v.dims())};
    if (sign > 0) roi.min.x = px;
    else roi.max.x = px;
    return roi;
}

// With the other side "none", the plane crops like a region of interest that
// keeps the normal's side, for every renderer, looking along the plane's
// normal (both ways) and across it. Planes: x = 29, the default (the centre,
// x = 48), and x = -5 outside the box (keeping all of it or none).
TEST_F(GlTest, CutWithNothingOnTheOtherSideEqualsTheCroppedRenderer) {
    const Volume v = headInside();
    for (const Look& look : looks(v)) {
        for (const char* view : {"+x", "-x", "+z", "-y"}) {
            for (int sign : {+1, -1}) {
                for (double px : {29.0, 48.0, -5.0}) {
                    const bool defaultPoint = px == 48.0;
                    const std::string what = look.renderer + ", view " + view + ", normal " +
                                             (sign > 0 ? "+x" : "-x") + ", plane x = " + std::to_string(px);
                    SCOPED_TRACE(what);
                    Scene cut = lookScene(v, view, look);
                    CuttingPlane plane;
                    if (!defaultPoint) plane.point = glm::dvec3(px, 17.0, 40.0);  // only x matters
                    plane.normal = glm::dvec3(2.0 * sign, 0.0, 0.0);           // any length
                    plane.otherRenderer = "none";
                    cut.cuttingPlane = plane;
                    Scene cropped = lookScene(v, view, look);
                    cropped.roi = halfBox(v, px, sign);
                    const Image got = render(v, cut);
                    Image want = render(v, cropped);
                    // Nothing kept: background everywhere (written out, since
                    // a region of interest outside the box is not empty in
                    // every view; see RegionOfInterestOutsideTheBoxIsEmpty).
                    if (px < 0 && sign < 0)
                        for (int y = 0; y < want.height; ++y)
                            for (int x = 0; x < want.width; ++x) want.set(x, y, glm::vec4(cut.background, 1.0f));
                    expectSameImage(got, want, kSameRenderTolerance, [](int, int) { return true; }, what);
                    // A plane inside the box must matter (except for the
                    // slicer's plane in views along x, which lies wholly on
                    // one side and shows all or nothing).
                    if (px > 0 && (look.renderer != "slicer" || std::string(view).find('x') == std::string::npos))
                        EXPECT_TRUE(imagesDiffer(want, render(v, lookScene(v, view, look))));
                }
            }
        }
    }
}

// The same with the trilinear default sampling (step 0.5) on an anisotropic
// volume, a plane across z. Samples start afresh at the plane as they do at a
// region of interest's face, so the two renders take the same samples (to
// float rounding; trilinear values then differ by ~1e-6 of the range).
TEST_F(GlTest, CutEqualsCropWithTrilinearSamplingOnAnisotropicData) {
    const Volume v = loadVolume(datasetPath("headsq.nrrd"));  // 64 x 64 x 93, spacing 3.2 3.2 1.5
    for (const char* view : {"+z", "-z", "+x"}) {
        for (int sign : {+1, -1}) {
            SCOPED_TRACE(std::string(view) + (sign > 0 ? ", normal +z" : ", normal -z"));
            Scene cut = axisViewScene(v, axisView(view), "mip");
            cut.interpolation = Interpolation::Trilinear;
            cut.step = 0.5;
            CuttingPlane plane;
            plane.point = glm::dvec3(10.0, 10.0, 41.0);
            plane.normal = glm::dvec3(0.0, 0.0, sign);
            cut.cuttingPlane = plane;
            Scene cropped = cut;
            cropped.cuttingPlane.reset();
            cropped.roi = RegionOfInterest{glm::dvec3(0.0), glm::dvec3(v.dims())};
            (sign > 0 ? cropped.roi->min.z : cropped.roi->max.z) = 41.0;
            expectSameImage(render(v, cut), render(v, cropped), kSameRenderTolerance, [](int, int) { return true; },
                            view);
        }
    }
}

// --- cutting plane, both sides -----------------------------------------------

// World x of the centre of pixel (px, py) of a view whose rays run parallel
// to x = const planes.
double pixelWorldX(const Volume& v, const Scene& scene, int px, int py) {
    const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
    glm::dvec3 o, d;
    cam.ray(px + 0.5, py + 0.5, &o, &d);
    return o.x;
}

// A view parallel to the plane: every ray lies in one half-space, so each
// part of the image is that side's renderer alone (cropped to its half).
TEST_F(GlTest, BothSidesSeenAcrossThePlaneEachEqualTheirRendererAlone) {
    const Volume v = headInside();
    const double px = 37.0;
    const Look positive = {"mip", std::nullopt, {}};
    for (const Look& negative : {Look{"minip", greenish(v), {}}, Look{"composite", greenish(v), {{"shading", 0.0}}},
                                 Look{"average", std::nullopt, {}}}) {
        for (const char* view : {"+z", "-y", "-z"}) {
            const std::string what = std::string("other side ") + negative.renderer + ", view " + view;
            SCOPED_TRACE(what);
            Scene cut = lookScene(v, view, positive);
            CuttingPlane plane;
            plane.point = glm::dvec3(px, 0.0, 0.0);
            plane.normal = glm::dvec3(1.0, 0.0, 0.0);
            plane.otherRenderer = negative.renderer;
            plane.otherTransferFunction = negative.tf;
            plane.otherParameters = negative.parameters;
            cut.cuttingPlane = plane;
            const Image got = render(v, cut);

            Scene right = lookScene(v, view, positive);
            right.roi = halfBox(v, px, +1);
            Scene left = lookScene(v, view, negative);
            left.roi = halfBox(v, px, -1);
            const Image wantRight = render(v, right), wantLeft = render(v, left);
            // Pixels within a thousandth of a voxel of the plane could go
            // either way; pixel centres here sit on voxel centres.
            auto side = [&](int x, int y) { return pixelWorldX(v, cut, x, y) - px * v.spacing().x; };
            expectSameImage(got, wantRight, kSameRenderTolerance, [&](int x, int y) { return side(x, y) > 1e-3; },
                            what + ", positive side");
            expectSameImage(got, wantLeft, kSameRenderTolerance, [&](int x, int y) { return side(x, y) < -1e-3; },
                            what + ", negative side");
            // The two sides must look different, or the test could not tell
            // them apart.
            EXPECT_TRUE(imagesDiffer(wantLeft, render(v, [&] {
                Scene s = left;
                s.renderer = positive.renderer;
                s.transferFunction.reset();
                s.parameters.clear();
                return s;
            }())));
        }
    }
}

// Looking through the plane, the half the ray enters first lies in front.
// Grey MIP output is opaque, so the image is the front half's MIP alone: the
// negative side (z < plane) for +z, the positive side for -z; with the
// normal flipped, the other way round. The other side draws a MinIP, which
// would show if the halves were laid the wrong way round.
TEST_F(GlTest, LookingThroughThePlaneShowsTheFrontHalf) {
    const Volume v = loadVolume(datasetPath("tooth.nrrd"));  // 103 x 94 x 161
    const double pz = 70.0;
    for (int sign : {+1, -1}) {
        for (const char* view : {"+z", "-z"}) {
            for (const char* other : {"mip", "minip"}) {
                const std::string what = std::string("view ") + view + ", normal " + (sign > 0 ? "+z" : "-z") +
                                         ", other side " + other;
                SCOPED_TRACE(what);
                Scene cut = axisViewScene(v, axisView(view), "mip");
                cut.background = glm::vec3(0.2f, 0.3f, 0.4f);
                CuttingPlane plane;
                plane.point = glm::dvec3(50.0, 50.0, pz);
                plane.normal = glm::dvec3(0.0, 0.0, sign);
                plane.otherRenderer = other;
                cut.cuttingPlane = plane;
                const Image got = render(v, cut);

                // The ray enters at z = 0 for +z: the front half is z < pz.
                const bool frontIsLowZ = std::string(view) == "+z";
                const bool frontIsPositive = frontIsLowZ == (sign < 0);
                Scene front = cut;
                front.cuttingPlane.reset();
                front.renderer = frontIsPositive ? "mip" : other;
                front.roi = RegionOfInterest{glm::dvec3(0.0), glm::dvec3(v.dims())};
                (frontIsLowZ ? front.roi->max.z : front.roi->min.z) = pz;
                Scene back = front;
                back.roi = RegionOfInterest{glm::dvec3(0.0), glm::dvec3(v.dims())};
                (frontIsLowZ ? back.roi->min.z : back.roi->max.z) = pz;
                back.renderer = frontIsPositive ? other : "mip";
                const Image want = render(v, front);
                expectSameImage(got, want, kSameRenderTolerance, [](int, int) { return true; }, what);
                EXPECT_TRUE(imagesDiffer(want, render(v, back))) << "front and back halves must differ";
            }
        }
    }
}

// --- command line --------------------------------------------------------------

// The implementation the fixture renders with ($VOXLAB_IMPLEMENTATION), passed
// on to the command line too.
std::string implementationOption() {
    const char* impl = std::getenv("VOXLAB_IMPLEMENTATION");
    return impl ? std::string(" --implementation ") + impl : std::string();
}

// The plane x = 20 with normal +x keeps x >= 20 (off-centre: the phantom is
// symmetric about its centre, and the kept part must not contain a mirror
// image of the rest). Across the plane (+z), image columns x < 20 show the
// background and the others the MIP over z of the phantom's voxels; along it
// (+x, image right = -z) every pixel is the MIP over x >= 20. Exact voxel
// values through the PNG's rounding: within one level.
TEST(CuttingPlaneCli, CutNormalWithNothingOnTheOtherSideRenders) {
    const Volume v = makePhantom("phantom:shells:32");
    for (const std::string view : {"+z", "+x"}) {
        SCOPED_TRACE("view " + view);
        const std::string out = (std::filesystem::temp_directory_path() /
                                 ("voxlab_cut_" + std::to_string(::getpid()) + ".png")).string();
        const CommandResult r = runVoxlab("render --dataset phantom:shells:32 --renderer mip --view " + view +
                                          " --projection orthographic --size 32x32 --interpolation nearest "
                                          "--step 1 --window 0,255 --background 0.2,0.2,0.2 --cut-normal 1,0,0 --cut-point 20,3,7 "
                                          "--cut-renderer none --out " + out + implementationOption());
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Image img = loadPng(out);
        std::remove(out.c_str());
        ASSERT_EQ(img.width, 32);
        ASSERT_EQ(img.height, 32);
        for (int y = 0; y < 32; ++y)
            for (int px = 0; px < 32; ++px) {
                double want = 0.0;
                if (view == "+z") {
                    for (int z = 0; z < 32; ++z) want = std::max(want, v.value(px, y, z));
                    if (px < 20) want = 0.2 * 255.0;
                } else {
                    for (int x = 20; x < 32; ++x) want = std::max(want, v.value(x, y, 31 - px));
                }
                ASSERT_NEAR(img.at(px, y).r * 255.0, want, 1.0) << "pixel " << px << ", " << y;
            }
    }
}

TEST(CuttingPlaneCli, ZeroCutNormalIsAOneLineError) {
    const CommandResult r = runVoxlab("render --dataset phantom:shells:16 --size 8x8 --cut-normal 0,0,0 --out " +
                                      (std::filesystem::temp_directory_path() / "voxlab_cut_never.png").string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("voxlab: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("cut-normal"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(std::filesystem::temp_directory_path() / "voxlab_cut_never.png"));
}

}  // namespace
}  // namespace voxlab::testing
