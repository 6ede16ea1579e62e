// Gradients, on the CPU (computeGradients, histogram2D) and on the GPU (the
// "gradient" stage, seen through the slicer with gradient=1), against
// estimators written out here from their documented definitions
// (gradients.h, README):
//  - units: data units per unit length, the unit being the smallest voxel
//    spacing m. A field f = a X + b Y + c Z + d in world coordinates has
//    gradient (a, b, c) per world unit, i.e. (a, b, c) * m per unit length;
//  - central differences along axis x: (f[i+1] - f[i-1]) / (2 sx) * m, and
//    at a face the one-sided (f[1] - f[0]) / sx * m (or (f[n-1] - f[n-2]));
//  - Sobel: the same difference on the 3 x 3 lines around the axis, with
//    weights [1 2 1] x [1 2 1] / 16, cross neighbours clamped to the grid.
// Both are exact on linear fields, faces and edges included, which gives
// an oracle that needs no estimator at all; a quadratic field tells the
// estimators apart and checks the weights and the boundary rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>

#include "support/cpu_sampling.h"
#include "support/gl_fixture.h"
#include "voxlab/gradients.h"

namespace voxlab::testing {
namespace {

using Field = std::function<double(glm::dvec3)>;

// A float32 volume whose voxel (i,j,k) holds field(its world centre).
Volume fieldVolume(glm::ivec3 dims, glm::dvec3 spacing, const Field& field) {
    std::vector<std::uint8_t> bytes(std::size_t(dims.x) * dims.y * dims.z * 4);
    std::size_t idx = 0;
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i, ++idx) {
                const float f = float(field((glm::dvec3(i, j, k) + 0.5) * spacing));
                std::memcpy(&bytes[idx * 4], &f, 4);
            }
    return Volume(dims, VoxelType::Float32, spacing, bytes, "field");
}

// --- The oracle estimators, at voxel (i,j,k) -------------------------------

// d f / d(world) along `axis` at voxel p: central inside, one-sided at the
// two faces, 0 on an axis one voxel thick (nothing to difference).
double axisDerivative(const Volume& v, glm::ivec3 p, int axis) {
    const int n = v.dims()[axis];
    const double h = v.spacing()[axis];
    glm::ivec3 prev = p, next = p;
    --prev[axis], ++next[axis];
    if (n == 1) return 0.0;
    if (p[axis] == 0) return (clampedVoxel(v, next) - clampedVoxel(v, p)) / h;
    if (p[axis] == n - 1) return (clampedVoxel(v, p) - clampedVoxel(v, prev)) / h;
    return (clampedVoxel(v, next) - clampedVoxel(v, prev)) / (2.0 * h);
}

glm::dvec3 oracleCentral(const Volume& v, glm::ivec3 p) {
    const glm::dvec3 g(axisDerivative(v, p, 0), axisDerivative(v, p, 1), axisDerivative(v, p, 2));
    return g * v.minSpacing();
}

glm::dvec3 oracleSobel(const Volume& v, glm::ivec3 p) {
    glm::dvec3 g(0.0);
    const double weight[3] = {1.0, 2.0, 1.0};  // offsets -1, 0, +1
    for (int axis = 0; axis < 3; ++axis) {
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        for (int da = -1; da <= 1; ++da)
            for (int db = -1; db <= 1; ++db) {
                glm::ivec3 q = p;
                q[a] = std::clamp(p[a] + da, 0, v.dims()[a] - 1);
                q[b] = std::clamp(p[b] + db, 0, v.dims()[b] - 1);
                g[axis] += weight[da + 1] * weight[db + 1] / 16.0 * axisDerivative(v, q, axis);
            }
    }
    return g * v.minSpacing();
}

std::size_t indexOf(const Volume& v, glm::ivec3 p) {
    return std::size_t(p.x) + std::size_t(v.dims().x) * (std::size_t(p.y) + std::size_t(v.dims().y) * p.z);
}

std::string str(glm::dvec3 g) {
    return "(" + std::to_string(g.x) + ", " + std::to_string(g.y) + ", " + std::to_string(g.z) + ")";
}

// Compares computeGradients with `want` at every voxel; `tol` absolute per
// component.
void expectCpuGradients(const Volume& v, GradientEstimator e, const std::function<glm::dvec3(glm::ivec3)>& want,
                        double tol) {
    const std::vector<glm::vec3> got = computeGradients(v, e);
    ASSERT_EQ(got.size(), v.voxelCount());
    int bad = 0;
    std::string first;
    for (int k = 0; k < v.dims().z; ++k)
        for (int j = 0; j < v.dims().y; ++j)
            for (int i = 0; i < v.dims().x; ++i) {
                const glm::dvec3 g(got[indexOf(v, {i, j, k})]), w = want({i, j, k});
                const glm::dvec3 d = glm::abs(g - w);
                if (std::max({d.x, d.y, d.z}) > tol && bad++ == 0)
                    first = "voxel (" + std::to_string(i) + "," + std::to_string(j) + "," + std::to_string(k) +
                            "): got " + str(g) + ", want " + str(w);
            }
    EXPECT_EQ(bad, 0) << gradientEstimatorName(e) << ": " << first;
}

struct Ramp {
    glm::dvec3 slope;  // per world unit
    double offset;
    double operator()(glm::dvec3 p) const { return glm::dot(slope, p) + offset; }
};

const Ramp kRamps[] = {
    {{1.0, 0.0, 0.0}, 0.0},
    {{0.0, -2.5, 0.0}, 40.0},
    {{0.0, 0.0, 0.75}, -3.0},
    {{0.7, -1.3, 2.1}, 5.0},
};
const glm::dvec3 kSpacings[] = {{1.0, 1.0, 1.0}, {0.5, 1.25, 2.0}, {3.2, 3.2, 1.5}};

// Float32 storage rounds each value by 6e-8 relative; a difference over one
// voxel divides that by h and multiplies by m <= h: 1e-5 of the largest
// |value| (<= ~60 here) covers it with room.
double floatTolerance(const Volume& v) {
    return 1e-5 * std::max(std::abs(v.minValue()), std::abs(v.maxValue())) + 1e-6;
}

// ============================ CPU ===========================================

TEST(CpuGradients, LinearRampsGiveTheExactSlopeAtEveryVoxel) {
    for (const glm::dvec3& spacing : kSpacings)
        for (const Ramp& ramp : kRamps) {
            // 6 x 5 x 7: every voxel of the two smaller axes is on a face or
            // an edge; the corners have one-sided differences on all axes.
            const Volume v = fieldVolume({6, 5, 7}, spacing, ramp);
            const glm::dvec3 want = ramp.slope * std::min({spacing.x, spacing.y, spacing.z});
            SCOPED_TRACE("spacing " + str(spacing) + ", slope " + str(ramp.slope));
            for (GradientEstimator e : {GradientEstimator::Central, GradientEstimator::Sobel})
                expectCpuGradients(v, e, [&](glm::ivec3) { return want; }, floatTolerance(v));
        }
}

// An axis one voxel thick has nothing to difference: that component is 0,
// the others are still exact.
TEST(CpuGradients, SingleVoxelAxisHasZeroComponent) {
    const Ramp ramp{{0.5, 2.0, 3.0}, 1.0};
    const Volume v = fieldVolume({5, 4, 1}, {1.0, 2.0, 1.0}, ramp);
    for (GradientEstimator e : {GradientEstimator::Central, GradientEstimator::Sobel})
        expectCpuGradients(v, e, [&](glm::ivec3) { return glm::dvec3(0.5, 2.0, 0.0); }, floatTolerance(v));
}

// f = X^2 + 3 Y Z - 0.5 Z^2 on an anisotropic grid. Central differences are
// exact for quadratics inside (2X, 3Z, 3Y - Z); the one-sided face rule is
// off by h/2 times f'': (X+h)^2 - X^2 = h (2X + h), so 2X + sx at i = 0 and
// 2X - sx at i = n-1; -Z - sz/2 at k = 0 and -Z + sz/2 at k = n-1. This
// checks the oracle itself analytically, then the library against it.
TEST(CpuGradients, CentralDifferencesOnAQuadraticFollowTheFaceRule) {
    const glm::dvec3 s(0.8, 1.1, 1.7);
    const glm::ivec3 n(7, 6, 8);
    const Field f = [](glm::dvec3 p) { return p.x * p.x + 3.0 * p.y * p.z - 0.5 * p.z * p.z; };
    const Volume v = fieldVolume(n, s, f);
    const double m = 0.8;
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) {
                const glm::dvec3 p = (glm::dvec3(i, j, k) + 0.5) * s;
                glm::dvec3 d(2.0 * p.x, 3.0 * p.z, 3.0 * p.y - p.z);
                if (i == 0) d.x += s.x;
                if (i == n.x - 1) d.x -= s.x;
                if (k == 0) d.z -= 0.5 * s.z;
                if (k == n.z - 1) d.z += 0.5 * s.z;
                const glm::dvec3 o = oracleCentral(v, {i, j, k});
                ASSERT_NEAR(o.x, d.x * m, 1e-4);
                ASSERT_NEAR(o.y, d.y * m, 1e-4);
                ASSERT_NEAR(o.z, d.z * m, 1e-4);
            }
    expectCpuGradients(v, GradientEstimator::Central, [&](glm::ivec3 p) { return oracleCentral(v, p); },
                       floatTolerance(v));
    // Sobel averages the differences of neighbouring lines; it must match
    // the weighted oracle, faces included.
    expectCpuGradients(v, GradientEstimator::Sobel, [&](glm::ivec3 p) { return oracleSobel(v, p); },
                       floatTolerance(v));
}

// A field with cross terms of higher order, where Sobel's smoothing really
// changes the result: the weights [1 2 1]^2 / 16 matter.
TEST(CpuGradients, SobelMatchesTheWeightedOracleOnACubicField) {
    const glm::dvec3 s(1.0, 0.6, 1.4);
    const Field f = [](glm::dvec3 p) {
        return 0.05 * p.x * p.y * p.y + 0.1 * p.z * p.z * p.x - 0.02 * p.y * p.z * p.z;
    };
    const Volume v = fieldVolume({6, 9, 5}, s, f);
    // The two estimators disagree somewhere by far more than the tolerance,
    // so this test tells them apart.
    double differ = 0.0;
    for (int j = 0; j < 9; ++j)
        differ = std::max(differ, glm::length(oracleSobel(v, {2, j, 2}) - oracleCentral(v, {2, j, 2})));
    EXPECT_GT(differ, 0.01);
    expectCpuGradients(v, GradientEstimator::Sobel, [&](glm::ivec3 p) { return oracleSobel(v, p); },
                       floatTolerance(v));
    expectCpuGradients(v, GradientEstimator::Central, [&](glm::ivec3 p) { return oracleCentral(v, p); },
                       floatTolerance(v));
}

// ---------------------------- histogram2D -----------------------------------

TEST(CpuGradients, Histogram2DOfARampPutsEveryVoxelAtItsSlope) {
    // f = 2 X on spacing (0.5, 1, 1): slope 2 per world unit, 1 per unit
    // length (m = 0.5). Every voxel has the same magnitude, the largest, so
    // all of them sit in the top gradient bin; values spread evenly over x.
    const Volume v = fieldVolume({16, 3, 4}, {0.5, 1.0, 1.0}, Ramp{{2.0, 0.0, 0.0}, 0.0});
    for (GradientEstimator e : {GradientEstimator::Central, GradientEstimator::Sobel}) {
        SCOPED_TRACE(gradientEstimatorName(e));
        const Histogram2D h = histogram2D(v, 8, 10, e);
        ASSERT_EQ(h.counts.size(), std::size_t(8 * 10));
        EXPECT_NEAR(h.gradientMax, 1.0, 1e-5);
        EXPECT_DOUBLE_EQ(h.valueLo, v.minValue());
        EXPECT_DOUBLE_EQ(h.valueHi, v.maxValue());
        std::uint64_t total = 0;
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 8; ++x) {
                const std::uint64_t c = h.counts[std::size_t(y) * 8 + x];
                total += c;
                // Values 0.5, 1.5, ..., 15.5 over [0.5, 15.5] in 8 bins of
                // width 1.875: two x-columns of voxels per bin (values
                // 0.5 + 15 b/8 ... never on a bin edge), 3 * 4 voxels each.
                EXPECT_EQ(c, y == 9 ? 24u : 0u) << "bin (" << x << ", " << y << ")";
            }
        EXPECT_EQ(total, v.voxelCount());
    }
}

// On the sphere phantom the histogram's largest magnitude is the largest
// |gradient| computeGradients gives, and the counts add up to every voxel.
TEST(CpuGradients, Histogram2DMaximumIsTheLargestGradient) {
    const Volume v = makePhantom("phantom:sphere:24");
    for (GradientEstimator e : {GradientEstimator::Central, GradientEstimator::Sobel}) {
        SCOPED_TRACE(gradientEstimatorName(e));
        double biggest = 0.0;
        for (const glm::vec3& g : computeGradients(v, e)) biggest = std::max(biggest, double(glm::length(g)));
        const Histogram2D h = histogram2D(v, 64, 32, e);
        EXPECT_NEAR(h.gradientMax, biggest, 1e-6);
        // The ramp of width 4 gives magnitudes of about 1/4; central
        // differences across the clamp at the ramp's ends give less, never more.
        EXPECT_GT(h.gradientMax, 0.2);
        EXPECT_LT(h.gradientMax, 0.3);
        std::uint64_t total = 0;
        for (std::uint64_t c : h.counts) total += c;
        EXPECT_EQ(total, v.voxelCount());
        // Voxels far from the surface (value 0 or 1) have gradient 0: the
        // bottom gradient row holds at least the inside and outside bulk.
        EXPECT_GT(h.counts[0] + h.counts[63], v.voxelCount() / 2);
    }
}

// ============================ GPU ===========================================

struct GpuCase {
    int sobel, precomputed;
};

std::string caseName(GpuCase c) {
    return std::string(c.sobel ? "sobel" : "central") + (c.precomputed ? "_precomputed" : "_on_the_fly");
}

// The slicer with gradient=1 shows |grad f| through the window; the float
// image is read back unrounded, so the magnitude is lo + grey (hi - lo).
Image renderGradientSlice(const Volume& v, const CameraSpec& cam, int w, int h, double offset, GpuCase c,
                          glm::dvec2 window) {
    Scene scene;
    scene.renderer = "slicer";
    scene.camera = cam;
    scene.width = w, scene.height = h;
    scene.interpolation = Interpolation::Trilinear;
    scene.window = window;
    scene.parameters["gradient"] = 1;
    scene.parameters["offset"] = offset;
    scene.parameters["sobel"] = c.sobel;
    scene.parameters["precomputed_gradients"] = c.precomputed;
    GlTest::engine().setVolume(v);
    return GlTest::engine().render(scene);
}

void PrintTo(const GpuCase& c, std::ostream* os) { *os << caseName(c); }

class GpuGradients : public GlTest, public ::testing::WithParamInterface<GpuCase> {};

// On a linear ramp every estimator is exact at every point of the box: the
// differences are taken between points clamped into the range of voxel
// centres, where trilinear interpolation of a linear field is the field
// itself (and a precomputed, linearly filtered gradient volume is constant).
// So the GPU must show |slope| * m at every pixel whose plane point lies in
// the box, faces and edges included. Tolerance: 1e-4 relative; float
// arithmetic on values up to ~60 differenced over a voxel gives ~1e-5.
TEST_P(GpuGradients, LinearRampShowsTheExactSlopeMagnitude) {
    const GpuCase c = GetParam();
    CameraSpec axis;
    axis.view = "+z";
    axis.projection = Projection::Orthographic;
    CameraSpec side = axis;
    side.view = "-x";
    CameraSpec orbit;
    orbit.azimuth = 35.0, orbit.elevation = -25.0;
    orbit.projection = Projection::Orthographic;
    double worst = 0.0;  // largest relative error seen
    for (const glm::dvec3& spacing : kSpacings)
        for (const Ramp& ramp : kRamps) {
            const Volume v = fieldVolume({10, 8, 9}, spacing, ramp);
            const double want = glm::length(ramp.slope) * v.minSpacing();
            const glm::dvec2 window(0.0, 2.0 * want);
            for (const CameraSpec& cam : {axis, side, orbit})
                // The plane through the centre, and one near the front face
                // (3.8 units of m before the centre: for the thin axes this
                // is within a voxel of the face).
                for (double offset : {0.0, -3.8}) {
                    SCOPED_TRACE("spacing " + str(spacing) + ", slope " + str(ramp.slope) + ", view " +
                                 (cam.view.empty() ? "orbit" : cam.view) + ", offset " + std::to_string(offset));
                    const int size = 40;
                    const Image img = renderGradientSlice(v, cam, size, size, offset, c, window);
                    const Camera camera = Camera::make(cam, v.extent(), size, size);
                    const glm::dvec3 planePoint = 0.5 * v.extent() + offset * v.minSpacing() * camera.forward;
                    int checked = 0, bad = 0;
                    std::string first;
                    for (int py = 0; py < size; ++py)
                        for (int px = 0; px < size; ++px) {
                            glm::dvec3 o, d;
                            camera.ray(px + 0.5, py + 0.5, &o, &d);
                            const double t = glm::dot(planePoint - o, camera.forward) / glm::dot(d, camera.forward);
                            const glm::dvec3 p = o + t * d;
                            // Clear of the box's faces by 1e-3 voxel, so that
                            // float rounding cannot put the point outside.
                            const glm::dvec3 margin = 1e-3 * spacing;
                            if (glm::any(glm::lessThan(p, margin)) ||
                                glm::any(glm::greaterThan(p, v.extent() - margin)))
                                continue;
                            ++checked;
                            const double got = window.x + img.at(px, py).r * (window.y - window.x);
                            worst = std::max(worst, std::abs(got - want) / want);
                            if (std::abs(got - want) > 1e-4 * want && bad++ == 0)
                                first = "pixel (" + std::to_string(px) + ", " + std::to_string(py) +
                                        ") at " + str(p) + ": |grad| " + std::to_string(got) + ", want " +
                                        std::to_string(want);
                        }
                    EXPECT_GT(checked, 50);
                    EXPECT_EQ(bad, 0) << first;
                }
        }
    std::printf("[ measured ] %s: largest relative error of |grad| on ramps %.2e\n", caseName(c).c_str(), worst);
}

// A smooth non-linear field with mixed terms, for the GPU checks below.
double mixedField(glm::dvec3 p) {
    return 0.5 * p.x * p.x + 0.8 * p.x * p.y * p.z - 0.3 * p.z * p.z * p.y + 2.0 * p.y;
}

// On a quadratic field the estimators differ and the face rule matters. The
// +z view with one pixel per voxel (sx = sy) and the plane through the
// centres of layer k puts every pixel on a voxel centre, where the
// on-the-fly estimators sample voxel centres only (trilinear weights
// vanish) and the precomputed volume is read at its texels: the GPU must
// show the magnitude of the discrete estimator at that voxel. Layers 0 and
// n-1 are the faces. Tolerance 1e-4 relative (+1e-4 absolute): float
// arithmetic on values up to ~200.
TEST_P(GpuGradients, QuadraticFieldShowsTheDiscreteEstimatorAtVoxelCentres) {
    const GpuCase c = GetParam();
    const glm::dvec3 s(0.8, 0.8, 1.3);
    const glm::ivec3 n(12, 10, 7);
    const Volume v = fieldVolume(n, s, mixedField);
    double biggest = 0.0;
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) {
                const glm::dvec3 g = c.sobel ? oracleSobel(v, {i, j, k}) : oracleCentral(v, {i, j, k});
                biggest = std::max(biggest, glm::length(g));
            }
    const glm::dvec2 window(0.0, 1.25 * biggest);
    CameraSpec cam;
    cam.view = "+z";
    cam.projection = Projection::Orthographic;
    double worst = 0.0;  // largest error relative to |grad| + 1
    for (int k : {0, 1, 3, n.z - 1}) {
        SCOPED_TRACE("layer " + std::to_string(k));
        const double offset = ((k + 0.5) * s.z - 0.5 * v.extent().z) / v.minSpacing();
        const Image img = renderGradientSlice(v, cam, n.x, n.y, offset, c, window);
        int bad = 0;
        std::string first;
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) {
                const glm::dvec3 g = c.sobel ? oracleSobel(v, {i, j, k}) : oracleCentral(v, {i, j, k});
                const double want = glm::length(g);
                const double got = window.x + img.at(i, j).r * (window.y - window.x);
                worst = std::max(worst, std::abs(got - want) / (want + 1.0));
                if (std::abs(got - want) > 1e-4 * want + 1e-4 && bad++ == 0)
                    first = "voxel (" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) +
                            "): |grad| " + std::to_string(got) + ", want " + std::to_string(want) + " from " + str(g);
            }
        EXPECT_EQ(bad, 0) << first;
    }
    std::printf("[ measured ] %s: largest error of |grad| on the quadratic %.2e\n", caseName(c).c_str(), worst);
}

// --- The on-the-fly estimators between voxels --------------------------------
// gradient.glsl documents them at any point p: along axis a, difference the
// interpolated field at p -+ h e_a, both clamped into the range of voxel
// centres [h/2, extent - h/2], over the distance left between them; Sobel
// averages that over the 3 x 3 parallel lines at +-1 voxel across (not
// clamped: the sampler's clamp-to-edge continues the border voxels
// outwards). Both come from tests/support/cpu_sampling.h (cpuCentralGradient,
// cpuSobelGradient).

// The precomputed path instead reads the voxels' gradients (computed on the
// CPU with the discrete estimator), linearly interpolated like the volume.
glm::dvec3 interpolatedVoxelGradient(const Volume& v, glm::dvec3 p, bool sobel) {
    const glm::dvec3 u = p / v.spacing() - 0.5;
    const glm::dvec3 base = glm::floor(u), w = u - base;
    glm::dvec3 sum(0.0);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 bit((corner >> 0) & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        double weight = 1.0;
        for (int a = 0; a < 3; ++a) weight *= bit[a] ? w[a] : 1.0 - w[a];
        const glm::ivec3 q = glm::clamp(glm::ivec3(base) + bit, glm::ivec3(0), v.dims() - 1);
        sum += weight * (sobel ? oracleSobel(v, q) : oracleCentral(v, q));
    }
    return sum;
}

// The same quadratic-and-cubic field seen obliquely, on planes that cut
// voxels anywhere: the on-the-fly estimators must equal their definitions
// at every plane point in the box, faces and corners included (so a stage
// that differences at +-h/2, which agrees at voxel centres, is told apart);
// the precomputed gradients must equal the voxels' gradients interpolated.
// Tolerance 1e-4 relative (+1e-4): float positions (~1e-6 voxel) times the
// field's gradient, and float weights, give ~1e-5 (measured 1e-6).
TEST_P(GpuGradients, NonLinearFieldMatchesTheDefinitionBetweenVoxels) {
    const GpuCase c = GetParam();
    const glm::dvec3 s(0.8, 1.0, 1.3);
    const glm::ivec3 n(11, 9, 8);
    const Volume v = fieldVolume(n, s, mixedField);
    CameraSpec orbit;
    orbit.azimuth = 40.0, orbit.elevation = 25.0;
    orbit.projection = Projection::Orthographic;
    const int size = 48;
    // The precomputed volume goes through the GPU's own linear filtering,
    // whose weights have only 8 bits on many GPUs (llvmpipe: float): each
    // axis' weight may then be off by 1/512, moving a component by up to
    // 1/512 of the largest change between neighbouring voxels per axis.
    double filterSlack = 0.0;
    if (c.precomputed) {
        double change = 0.0;
        for (int k = 0; k < n.z; ++k)
            for (int j = 0; j < n.y; ++j)
                for (int i = 0; i < n.x; ++i)
                    for (int a = 0; a < 3; ++a) {
                        glm::ivec3 q(i, j, k);
                        if (++q[a] >= n[a]) continue;
                        const glm::dvec3 d = c.sobel ? oracleSobel(v, q) - oracleSobel(v, {i, j, k})
                                                     : oracleCentral(v, q) - oracleCentral(v, {i, j, k});
                        change = std::max(change, glm::length(d));
                    }
        filterSlack = 3.0 * change / 512.0;
    }
    double worst = 0.0;
    for (double offset : {0.0, 2.7, -4.1}) {
        SCOPED_TRACE("offset " + std::to_string(offset));
        const Camera camera = Camera::make(orbit, v.extent(), size, size);
        const glm::dvec3 planePoint = 0.5 * v.extent() + offset * v.minSpacing() * camera.forward;
        // Plane points first, to choose the window.
        std::vector<std::pair<glm::ivec2, double>> want;
        double biggest = 0.0;
        for (int py = 0; py < size; ++py)
            for (int px = 0; px < size; ++px) {
                glm::dvec3 o, d;
                camera.ray(px + 0.5, py + 0.5, &o, &d);
                const glm::dvec3 p = o + glm::dot(planePoint - o, camera.forward) / glm::dot(d, camera.forward) * d;
                const glm::dvec3 margin = 1e-3 * s;
                if (glm::any(glm::lessThan(p, margin)) || glm::any(glm::greaterThan(p, v.extent() - margin)))
                    continue;
                const double g = glm::length(c.precomputed ? interpolatedVoxelGradient(v, p, c.sobel)
                                                           : c.sobel ? cpuSobelGradient(v, p) : cpuCentralGradient(v, p));
                want.push_back({{px, py}, g});
                biggest = std::max(biggest, g);
            }
        ASSERT_GT(want.size(), 200u);
        const glm::dvec2 window(0.0, 1.25 * biggest);
        const Image img = renderGradientSlice(v, orbit, size, size, offset, c, window);
        int bad = 0;
        std::string first;
        for (const auto& [px, g] : want) {
            const double got = window.x + img.at(px.x, px.y).r * (window.y - window.x);
            worst = std::max(worst, std::abs(got - g) / (g + 1.0));
            if (std::abs(got - g) > 1e-4 * g + 1e-4 + filterSlack && bad++ == 0)
                first = "pixel (" + std::to_string(px.x) + ", " + std::to_string(px.y) + "): |grad| " +
                        std::to_string(got) + ", want " + std::to_string(g);
        }
        EXPECT_EQ(bad, 0) << first;
    }
    std::printf("[ measured ] %s: largest error of |grad| between voxels %.2e\n", caseName(c).c_str(), worst);
}

INSTANTIATE_TEST_SUITE_P(Estimators, GpuGradients,
                         ::testing::Values(GpuCase{0, 0}, GpuCase{1, 0}, GpuCase{0, 1}, GpuCase{1, 1}),
                         [](const auto& info) { return caseName(info.param); });

}  // namespace
}  // namespace voxlab::testing
