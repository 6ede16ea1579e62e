// The projection renderers minip, average, firsthit (value and depth) and
// slab_mip, against CPU projections of the voxel columns each pixel sees in
// orthographic axis views (nearest interpolation, step 1, one pixel per
// voxel; see support/axis_columns.h). Where samples are placed is worked out
// here from the README's sampling rule (sample m at t_entry + (m + 1/2) step,
// floor(length / step + 1/2) samples, step = scene step x smallest spacing),
// so anisotropic volumes, whose samples do not fall one per voxel along a
// coarse axis, are covered too. Every axis view, real datasets of every
// storage type and float phantoms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>
#include <sstream>

#include "support/axis_columns.h"
#include "support/gl_fixture.h"
#include "voxlab/camera.h"

namespace voxlab::testing {
namespace {

// Tolerance for grey outputs: one grey level (1/255). The expected grey
// values are exact; the GPU's come from float arithmetic on exact voxel
// values (at most ~1e-5 off), so the bound is loose on purpose, the
// suite-wide "within one 8-bit level" rule.
constexpr double kGreyTolerance = 1.0 / 255.0;

// One sample along a column: the value read (nearest voxel) and its
// distance from the box's entry face, in world units.
struct ColumnSample {
    double value;
    double distance;
};

// The samples a ray takes over [a, b] (distances from the box's entry face
// along the ray, world units; clipped to the box's depth). The column holds
// the voxel values front to back, voxel m covering [m s, (m+1) s] with s the
// spacing along the view. Returns false when a sample lies within 1e-4 voxel
// of a voxel boundary (nearest may pick either neighbour there).
bool columnSamples(const std::vector<double>& column, double spacing, double step, double a, double b,
                   std::vector<ColumnSample>* out) {
    out->clear();
    const int nVoxels = int(column.size());
    a = std::max(a, 0.0);
    b = std::min(b, nVoxels * spacing);
    if (!(b > a)) return true;
    const int n = int(std::floor((b - a) / step + 0.5));
    for (int m = 0; m < n; ++m) {
        const double d = a + (m + 0.5) * step;
        const double u = d / spacing;
        const double r = std::round(u);
        if (std::abs(u - r) < 1e-4 && r > 0 && r < nVoxels) return false;
        const int k = std::clamp(int(std::floor(u)), 0, nVoxels - 1);
        out->push_back({column[k], d});
    }
    return true;
}

// Where the ray of pixel (px, py) enters the box (slab method), and the
// depth display's grey for a distance t along it: 1 - (t - t_near) / (2 rho)
// with rho the bounding-sphere radius and t_near where the ray reaches it.
struct PixelRay {
    glm::dvec3 origin, direction;
    double tEntry = 0.0;

    double depthGrey(const Volume& v, double t) const {
        const glm::dvec3 c = 0.5 * v.extent();
        const double rho = 0.5 * glm::length(v.extent());
        const double tNear = glm::dot(c - origin, direction) - rho;
        return std::clamp(1.0 - (t - tNear) / (2.0 * rho), 0.0, 1.0);
    }
};

PixelRay pixelRay(const Volume& v, const Scene& scene, int px, int py) {
    const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
    PixelRay ray;
    cam.ray(px + 0.5, py + 0.5, &ray.origin, &ray.direction);
    double t0 = -1e300;
    for (int a = 0; a < 3; ++a) {
        if (ray.direction[a] == 0.0) continue;  // axis views: inside on this axis (pixel is in the box)
        const double ta = (0.0 - ray.origin[a]) / ray.direction[a];
        const double tb = (v.extent()[a] - ray.origin[a]) / ray.direction[a];
        t0 = std::max(t0, std::min(ta, tb));
    }
    ray.tEntry = std::max(t0, 0.0);
    return ray;
}

double windowGrey(double value, glm::dvec2 window) {
    return std::clamp((value - window.x) / (window.y - window.x), 0.0, 1.0);
}

// What one pixel must show (rgb), or nothing to check.
using Expectation = std::optional<glm::dvec3>;

// Everything an oracle needs about one pixel of an axis view.
struct PixelContext {
    const Volume& volume;
    const AxisView& view;
    const Scene& scene;
    const PixelColumn& column;
    int px, py;
    double spacing() const { return volume.spacing()[view.fwdAxis]; }
    double step() const { return scene.step * volume.minSpacing(); }
    // Samples over the whole column; false when one is ambiguous.
    bool samples(std::vector<ColumnSample>* out, double a = 0.0, double b = 1e300) const {
        return columnSamples(column.values, spacing(), step(), a, b, out);
    }
};

// Renders the scene and compares every pixel with `oracle` (rgb within
// `tolerance`). Pixels outside the box must show the background; pixels on a
// voxel boundary are skipped (and must be rare). Also checks that the oracle
// asks for several different grey levels, so that a constant image cannot
// pass. Returns the grey levels (of red) expected.
template <class Oracle>
std::set<int> expectRender(const Volume& v, const AxisView& view, const Scene& scene, Oracle oracle,
                           double tolerance = kGreyTolerance, int minDistinctLevels = 8) {
    GlTest::engine().setVolume(v);
    const Image img = GlTest::engine().render(scene);
    const std::vector<PixelColumn> columns = axisColumns(v, view, scene.width, scene.height);
    int bad = 0, skipped = 0, checked = 0;
    std::set<int> levels;
    std::string first;
    for (int py = 0; py < scene.height; ++py)
        for (int px = 0; px < scene.width; ++px) {
            const PixelColumn& col = columns[std::size_t(py) * scene.width + px];
            Expectation want;
            if (!col.inside) {
                want = glm::dvec3(scene.background);
            } else if (!col.ambiguous) {
                want = oracle(PixelContext{v, view, scene, col, px, py});
            }
            if (!want) {
                ++skipped;
                continue;
            }
            ++checked;
            levels.insert(int(std::lround(want->r * 255.0)));
            const glm::vec4 got = img.at(px, py);
            const double err = std::max({std::abs(got.r - want->r), std::abs(got.g - want->g),
                                         std::abs(got.b - want->b)});
            if (err > tolerance && bad++ == 0) {
                std::ostringstream s;
                s << "pixel (" << px << ", " << py << "): got (" << got.r << ", " << got.g << ", " << got.b
                  << "), CPU gives (" << want->r << ", " << want->g << ", " << want->b << ")";
                first = s.str();
            }
        }
    EXPECT_EQ(bad, 0) << bad << " of " << checked << " pixels off; first " << first;
    EXPECT_LT(skipped, scene.width * scene.height / 10) << "too many pixels on voxel boundaries";
    EXPECT_GE(int(levels.size()), minDistinctLevels) << "the expected image is too uniform to test anything";
    return levels;
}

// A sub-box [lo, hi) of a volume's voxels, as a volume of its own (for
// minimum projections inside a body, away from the air around it).
Volume crop(const Volume& v, glm::ivec3 lo, glm::ivec3 hi) {
    const glm::ivec3 d = hi - lo;
    const std::size_t size = voxelTypeSize(v.type());
    std::vector<std::uint8_t> bytes(std::size_t(d.x) * d.y * d.z * size);
    const auto* src = static_cast<const std::uint8_t*>(v.data());
    std::size_t o = 0;
    for (int k = lo.z; k < hi.z; ++k)
        for (int j = lo.y; j < hi.y; ++j)
            for (int i = lo.x; i < hi.x; ++i, o += size) {
                const std::size_t index = i + std::size_t(v.dims().x) * (j + std::size_t(v.dims().y) * k);
                std::memcpy(&bytes[o], src + index * size, size);
            }
    return Volume(d, v.type(), v.spacing(), bytes, v.name() + "-crop");
}

// Real datasets (8-bit non-cubic, 16-bit anisotropic, signed anisotropic),
// the inside of two bodies (so that minima are not all air), float phantoms.
Volume testVolume(const std::string& name) {
    if (name == "cthead-inside") return crop(loadVolume(datasetPath("cthead.nrrd")), {80, 70, 30}, {176, 150, 80});
    if (name == "headsq-inside") return crop(loadVolume(datasetPath("headsq.nrrd")), {18, 16, 25}, {46, 48, 75});
    if (name == "bonsai-inside") return crop(loadVolume(datasetPath("bonsai.nrrd")), {90, 60, 90}, {166, 200, 166});
    return namedVolume(name);
}

std::string paramName(const std::string& s0) {
    std::string s = s0.substr(0, s0.find('.'));
    for (char& c : s)
        if (!isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
}

class Projections : public GlTest, public ::testing::WithParamInterface<std::string> {};

// Average: the mean of the samples along the ray.
TEST_P(Projections, AverageEqualsTheColumnMean) {
    const Volume v = testVolume(GetParam());
    const glm::dvec2 window(v.minValue(), v.maxValue());
    for (const AxisView& view : kAxisViews) {
        SCOPED_TRACE(std::string("view ") + view.name);
        const Scene scene = axisViewScene(v, view, "average");
        expectRender(v, view, scene, [&](const PixelContext& p) -> Expectation {
            std::vector<ColumnSample> s;
            if (!p.samples(&s) || s.empty()) return std::nullopt;
            double sum = 0.0;
            for (const ColumnSample& x : s) sum += x.value;
            return glm::dvec3(windowGrey(sum / s.size(), window));
        });
    }
}

// MinIP: the smallest sample along the ray. Checked on volumes whose columns
// have varied minima (in a whole head or bonsai nearly every ray meets air,
// and the image would be uniform).
class MinimumProjection : public GlTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(MinimumProjection, MinipEqualsTheColumnMinimum) {
    const Volume v = testVolume(GetParam());
    const glm::dvec2 window(v.minValue(), v.maxValue());
    for (const AxisView& view : kAxisViews) {
        SCOPED_TRACE(std::string("view ") + view.name);
        const Scene scene = axisViewScene(v, view, "minip");
        expectRender(v, view, scene, [&](const PixelContext& p) -> Expectation {
            std::vector<ColumnSample> s;
            if (!p.samples(&s) || s.empty()) return std::nullopt;
            double m = 1e300;
            for (const ColumnSample& x : s) m = std::min(m, x.value);
            return glm::dvec3(windowGrey(m, window));
        });
    }
}

INSTANTIATE_TEST_SUITE_P(VolumesWithVariedMinima, MinimumProjection,
                         ::testing::Values(std::string("tooth.nrrd"),     // uint8, non-cubic
                                           std::string("cthead-inside"),  // uint16, spacing 1 1 2
                                           std::string("headsq-inside"),  // int16, spacing 3.2 3.2 1.5
                                           std::string("phantom:marschner-lobb:32")),  // float32
                         [](const auto& info) { return paramName(info.param); });

// A threshold between the data's values: half-way between integers for
// integer data (no voxel equals it, whatever float rounding does), and far
// from every voxel value for float data.
double thresholdFor(const Volume& v, double fraction) {
    const double t = v.minValue() + fraction * (v.maxValue() - v.minValue());
    if (v.type() != VoxelType::Float32) return std::floor(t) + 0.5;
    return t;
}

// First hit: the first sample at or above the threshold, shown by its value
// through the window, or (depth = 1) by the depth grey of that sample's
// position. Rays without a hit show the background.
TEST_P(Projections, FirstHitShowsTheFirstSampleAtOrAboveTheThreshold) {
    const Volume v = testVolume(GetParam());
    const glm::dvec2 window(v.minValue(), v.maxValue());
    const double range = v.maxValue() - v.minValue();
    std::set<int> depthLevels;
    for (double fraction : {0.3, 0.6}) {
        const double threshold = thresholdFor(v, fraction);
        for (const AxisView& view : kAxisViews) {
            for (int depth : {0, 1}) {
                SCOPED_TRACE(std::string("view ") + view.name + ", threshold " + std::to_string(threshold) +
                             (depth ? ", depth" : ", value"));
                Scene scene = axisViewScene(v, view, "firsthit");
                scene.parameters["threshold"] = threshold;
                scene.parameters["depth"] = depth;
                scene.background = glm::vec3(0.1f, 0.2f, 0.3f);  // misses are told apart from black hits
                const std::set<int> levels = expectRender(
                    v, view, scene,
                    [&](const PixelContext& p) -> Expectation {
                        std::vector<ColumnSample> s;
                        if (!p.samples(&s)) return std::nullopt;
                        for (const ColumnSample& x : s) {
                            // Float data: a value within float rounding of the
                            // threshold could go either way.
                            if (std::abs(x.value - threshold) < 1e-5 * range) return std::nullopt;
                            if (x.value < threshold) continue;
                            if (!depth) return glm::dvec3(windowGrey(x.value, window));
                            const PixelRay ray = pixelRay(v, scene, p.px, p.py);
                            return glm::dvec3(ray.depthGrey(v, ray.tEntry + x.distance));
                        }
                        return glm::dvec3(scene.background);
                    },
                    // One view may see a single material, or every ray may
                    // hit at its first sample (one depth); the depth images
                    // together must vary.
                    kGreyTolerance, 1);
                if (depth) depthLevels.insert(levels.begin(), levels.end());
            }
        }
    }
    EXPECT_GE(int(depthLevels.size()), 16) << "the depth images are too uniform to test anything";
}

// "At or above": a sample equal to the threshold is a hit. Float data make
// the equality exact on the GPU (the texel is the float itself, and the
// threshold a float with the same value): in ramp-x, voxel i holds i + 1/2,
// so with threshold 10.5 the hit is voxel 10, not 11, in both x views.
TEST_F(GlTest, FirstHitThresholdIsInclusive) {
    const Volume v = makePhantom("phantom:ramp-x:24");
    for (const AxisView& view : {kAxisViews[2], kAxisViews[3]}) {  // +x, -x
        for (int depth : {0, 1}) {
            SCOPED_TRACE(std::string("view ") + view.name + (depth ? ", depth" : ", value"));
            Scene scene = axisViewScene(v, view, "firsthit");
            scene.parameters["threshold"] = 10.5;
            scene.parameters["depth"] = depth;
            engine().setVolume(v);
            const Image img = engine().render(scene);
            // +x meets voxel 10 (value 10.5) first; -x meets 23 first.
            const int voxel = view.fwdSign > 0 ? 10 : 23;
            const double distance = view.fwdSign > 0 ? voxel + 0.5 : 24 - (voxel + 0.5);
            for (int py = 0; py < scene.height; py += 5)
                for (int px = 0; px < scene.width; px += 5) {
                    const PixelRay ray = pixelRay(v, scene, px, py);
                    const double want = depth ? ray.depthGrey(v, ray.tEntry + distance)
                                              : windowGrey(voxel + 0.5, {v.minValue(), v.maxValue()});
                    ASSERT_NEAR(img.at(px, py).r, want, kGreyTolerance) << "pixel " << px << ", " << py;
                }
        }
    }
}

// Slab MIP: the maximum over the samples inside the slab, which the ray
// starts afresh at the slab's near face. Slab faces sit on voxel boundaries
// along the view, so that along an axis with the smallest spacing the step-1
// samples land on voxel centres and the answer is the maximum over the
// voxels whose centres lie inside the slab; along a coarser axis (headsq's x
// and y, cthead's z) it is the maximum over the voxels the samples fall in.
// Some slabs stick out of the box.
TEST_P(Projections, SlabMipEqualsTheMaximumOverTheSlab) {
    const Volume v = testVolume(GetParam());
    const glm::dvec2 window(v.minValue(), v.maxValue());
    for (const AxisView& view : kAxisViews) {
        const int n = v.dims()[view.fwdAxis];
        const double s = v.spacing()[view.fwdAxis], ms = v.minSpacing();
        const double depthWorld = n * s;
        // [first, last) voxel layers counted from the front face of the view.
        const std::pair<int, int> slabs[] = {{n / 4, n / 4 + 5}, {n / 2, n / 2 + 1}, {-3, 4}, {n - 6, n + 2}};
        for (auto [first, last] : slabs) {
            SCOPED_TRACE(std::string("view ") + view.name + ", layers [" + std::to_string(first) + ", " +
                         std::to_string(last) + ")");
            Scene scene = axisViewScene(v, view, "slab_mip");
            const double a = first * s, b = last * s;  // distances from the front face
            // The slab's centre plane sits at offset * ms along the view from
            // the box centre, i.e. at depth depthWorld/2 + offset*ms.
            scene.parameters["offset"] = ((a + b) / 2.0 - depthWorld / 2.0) / ms;
            scene.parameters["thickness"] = (b - a) / ms;
            expectRender(
                v, view, scene,
                [&](const PixelContext& p) -> Expectation {
                    double m = -1e300;
                    if (s == ms) {
                        // Samples one per voxel: the voxels whose centres
                        // lie inside the slab.
                        for (int k = std::max(first, 0); k < std::min(last, n); ++k)
                            m = std::max(m, p.column.values[k]);
                    } else {
                        // A coarser axis: the voxels the samples fall in.
                        std::vector<ColumnSample> smp;
                        if (!p.samples(&smp, a, b)) return std::nullopt;
                        for (const ColumnSample& x : smp) m = std::max(m, x.value);
                    }
                    if (m == -1e300) return glm::dvec3(scene.background);
                    return glm::dvec3(windowGrey(m, window));
                },
                // Slabs at the box's faces may hold nothing but air.
                kGreyTolerance, first < 0 || last > n ? 1 : 3);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(RealAndPhantomVolumes, Projections,
                         ::testing::Values(std::string("tooth.nrrd"),     // uint8, non-cubic
                                           std::string("cthead-inside"),  // uint16, spacing 1 1 2
                                           std::string("headsq.nrrd"),    // int16, spacing 3.2 3.2 1.5
                                           std::string("bonsai-inside"),  // uint8, non-cubic crop
                                           std::string("phantom:marschner-lobb:32"),  // float32
                                           std::string("phantom:shepp-logan:40")),    // float32
                         [](const auto& info) { return paramName(info.param); });

// Piecewise-linear transfer function written for the test: colour and alpha
// interpolated between neighbouring control points, clamped outside.
glm::dvec4 oracleTf(const std::vector<ControlPoint>& pts, double v) {
    auto at = [](const ControlPoint& c) { return glm::dvec4(glm::dvec3(c.color), c.alpha); };
    if (v <= pts.front().value) return at(pts.front());
    if (v >= pts.back().value) return at(pts.back());
    for (std::size_t i = 1; i < pts.size(); ++i)
        if (v <= pts[i].value) {
            const double t = (v - pts[i - 1].value) / (pts[i].value - pts[i - 1].value);
            return at(pts[i - 1]) + t * (at(pts[i]) - at(pts[i - 1]));
        }
    return at(pts.back());
}

// With a transfer function, minip and average show the projected value's
// colour times its opacity over the background: rgb a + (1 - a) background.
// Tolerance 1/255: the GPU's table is baked within 0.5/255 of the function.
TEST_F(GlTest, TransferFunctionColoursMinipAndAverage) {
    const Volume v = testVolume("cthead-inside");
    const std::vector<ControlPoint> pts = {{0.0, {0.0f, 0.0f, 1.0f}, 0.1f},
                                           {600.0, {1.0f, 0.5f, 0.0f}, 0.9f},
                                           {1200.0, {0.2f, 1.0f, 0.3f}, 0.4f},
                                           {2500.0, {1.0f, 1.0f, 1.0f}, 1.0f}};
    const glm::dvec3 bg(0.25, 0.5, 0.75);
    for (const char* renderer : {"minip", "average"}) {
        for (const AxisView& view : {kAxisViews[0], kAxisViews[3]}) {
            SCOPED_TRACE(std::string(renderer) + ", view " + view.name);
            Scene scene = axisViewScene(v, view, renderer);
            scene.transferFunction = TransferFunction(pts);
            scene.background = glm::vec3(bg);
            const bool isMin = std::string(renderer) == "minip";
            expectRender(v, view, scene, [&](const PixelContext& p) -> Expectation {
                std::vector<ColumnSample> s;
                if (!p.samples(&s) || s.empty()) return std::nullopt;
                double r = isMin ? 1e300 : 0.0;
                for (const ColumnSample& x : s) r = isMin ? std::min(r, x.value) : r + x.value;
                if (!isMin) r /= s.size();
                const glm::dvec4 c = oracleTf(pts, r);
                return glm::dvec3(c) * c.a + (1.0 - c.a) * bg;
            });
        }
    }
}

}  // namespace
}  // namespace voxlab::testing
