// Cubic reconstruction (the cubic stage: interpolations "catmull-rom" and
// "bspline") against oracles that do not use its code:
//  - polynomials: Catmull-Rom reproduces every quadratic, and the B-spline
//    on its prefiltered coefficients every cubic, exactly, away from the
//    borders (where the clamped taps break the pattern): values and
//    gradients of the slicer's plane through analytic fields, compared with
//    the fields themselves; trilinear reproduces neither (so the test bites);
//  - the B-spline interpolates: its coefficients (bspline.h), summed with
//    the closed-form basis beta3(x) = 2/3 - x^2 + |x|^3/2 (|x| < 1),
//    (2 - |x|)^3/6 (|x| < 2), reproduce every voxel, borders included; and
//    the GPU's B-spline equals the voxel values at their centres;
//  - random points: the GPU against a CPU evaluation written here with
//    Catmull-Rom as the cardinal spline 1/2 (2 p1 + (p2 - p0) t + ...) and
//    the B-spline through beta3, on a random volume with unequal spacings;
//  - the function check's reference outputs: the weights of the handout's
//    table, summing to 1, their derivatives summing to 0 and matching a
//    finite difference of the weights;
//  - the Marschner-Lobb signal: the error of each interpolation against
//    the analytic function at the slicer's points (docs/reconstruction.md).
// The slicer shows a value v as (v - lo) / (hi - lo) through the window, in
// float: the image is read back unrounded, so values are compared to float
// precision (1e-5 of the window here).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>

#include "support/gl_fixture.h"
#include "voxlab/bspline.h"
#include "voxlab/camera.h"
#include "voxlab/function_checks.h"
#include "voxlab/phantoms.h"

namespace voxlab::testing {
namespace {

using glm::dvec3;

Volume fieldVolume(glm::ivec3 d, dvec3 spacing, const std::function<double(dvec3)>& f) {
    std::vector<float> values;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i) values.push_back(float(f((dvec3(i, j, k) + 0.5) * spacing)));
    std::vector<std::uint8_t> bytes(values.size() * 4);
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return Volume(d, VoxelType::Float32, spacing, bytes, "field");
}

// The slicer's points: each pixel's ray meets the plane through the box's
// centre perpendicular to the view (offset 0).
struct SlicePoint {
    int x, y;
    dvec3 p;
};

std::vector<SlicePoint> slicePoints(const Volume& v, const Scene& scene) {
    const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
    const dvec3 centre = 0.5 * v.extent();
    std::vector<SlicePoint> out;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            dvec3 o, d;
            cam.ray(x + 0.5, y + 0.5, &o, &d);
            const double t = glm::dot(centre - o, cam.forward) / glm::dot(d, cam.forward);
            const dvec3 p = o + t * d;
            if (glm::all(glm::greaterThanEqual(p, dvec3(0.0))) && glm::all(glm::lessThanEqual(p, v.extent())))
                out.push_back({x, y, p});
        }
    return out;
}

Scene sliceScene(Interpolation interpolation, glm::dvec2 window, bool gradient = false) {
    Scene s;
    s.renderer = "slicer";
    s.camera.azimuth = 23.0, s.camera.elevation = 17.0;
    s.camera.projection = Projection::Orthographic;
    s.width = s.height = 96;
    s.interpolation = interpolation;
    s.window = window;
    if (gradient) s.parameters["gradient"] = 1.0;
    return s;
}

// Distance from p to the nearest face of the box, in voxels of the coarsest axis.
double voxelsFromBorder(const Volume& v, dvec3 p) {
    const dvec3 u = p / v.spacing();
    double d = 1e300;
    for (int a = 0; a < 3; ++a) d = std::min({d, u[a], v.dims()[a] - u[a]});
    return d;
}

struct Fit {
    double worst = 0.0;
    int compared = 0;
};

// The slicer's values (or gradient magnitudes) against f at the points at
// least `margin` voxels inside the box.
Fit compareSlice(const Volume& v, Interpolation interpolation, const std::function<double(dvec3)>& f,
                 glm::dvec2 window, double margin, bool gradient = false) {
    GlTest::engine().setVolume(v);
    const Scene scene = sliceScene(interpolation, window, gradient);
    const Image image = GlTest::engine().render(scene);
    Fit fit;
    for (const SlicePoint& s : slicePoints(v, scene)) {
        if (voxelsFromBorder(v, s.p) < margin) continue;
        const double shown = window.x + double(image.at(s.x, s.y).r) * (window.y - window.x);
        fit.worst = std::max(fit.worst, std::abs(shown - f(s.p)));
        ++fit.compared;
    }
    return fit;
}

class Cubic : public GlTest {};

TEST_F(Cubic, CatmullRomReproducesQuadraticsAndTheBsplineCubicsAwayFromTheBorders) {
    const dvec3 spacing(1.0, 1.4, 0.8);
    const auto quadratic = [](dvec3 p) { return 0.02 * p.x * p.x - 0.015 * p.y * p.z + 0.01 * p.z * p.z + 0.3 * p.y; };
    const auto cubic = [](dvec3 p) {
        const double x = p.x - 18.0;
        return 0.01 * x * x * x - 2e-3 * p.x * p.y + 4e-4 * p.z * p.z * p.y + 0.1 * p.z;
    };
    const glm::ivec3 dims(36, 30, 34);
    const Volume q = fieldVolume(dims, spacing, quadratic), c = fieldVolume(dims, spacing, cubic);
    const glm::dvec2 qw(q.minValue() - 1.0, q.maxValue() + 1.0), cw(c.minValue() - 1.0, c.maxValue() + 1.0);
    const Fit cr = compareSlice(q, Interpolation::CatmullRom, quadratic, qw, 2.5);
    const Fit bq = compareSlice(q, Interpolation::BSpline, quadratic, qw, 12.0);
    const Fit bc = compareSlice(c, Interpolation::BSpline, cubic, cw, 12.0);
    const Fit tri = compareSlice(q, Interpolation::Trilinear, quadratic, qw, 2.5);
    const Fit crCubic = compareSlice(c, Interpolation::CatmullRom, cubic, cw, 2.5);
    std::printf("quadratic (window %.1f): Catmull-Rom %.2e over %d points, B-spline %.2e, trilinear %.2e\n"
                "cubic (window %.1f): B-spline %.2e over %d points, Catmull-Rom %.2e\n",
                qw.y - qw.x, cr.worst, cr.compared, bq.worst, tri.worst, cw.y - cw.x, bc.worst, bc.compared,
                crCubic.worst);
    EXPECT_GT(cr.compared, 1000);
    EXPECT_GT(bc.compared, 200);
    // Float sums of 64 taps of values up to the window's size: 64 * 6e-8 = 4e-6 of it; 5e-6 allowed.
    const double floatTolerance = 5e-6;
    EXPECT_LE(cr.worst, floatTolerance * (qw.y - qw.x));
    EXPECT_LE(bq.worst, floatTolerance * (qw.y - qw.x));
    EXPECT_LE(bc.worst, floatTolerance * (cw.y - cw.x));
    // The oracle bites: the kernels that do not promise it miss by far more.
    EXPECT_GT(tri.worst, 20 * floatTolerance * (qw.y - qw.x)) << "trilinear cannot reproduce a quadratic";
    EXPECT_GT(tri.worst, 100 * cr.worst);
    EXPECT_GT(crCubic.worst, floatTolerance * (cw.y - cw.x)) << "Catmull-Rom is exact for quadratics only";
    EXPECT_GT(crCubic.worst, 50 * bc.worst);
}

TEST_F(Cubic, GradientsAreTheFieldsOwnDerivative) {
    // |grad f| in data units per unit length (the smallest spacing, 0.8).
    const dvec3 spacing(1.0, 1.4, 0.8);
    const auto quadratic = [](dvec3 p) { return 0.02 * p.x * p.x - 0.015 * p.y * p.z + 0.3 * p.y; };
    const auto gradient = [&](dvec3 p) {
        return 0.8 * glm::length(dvec3(0.04 * p.x, -0.015 * p.z + 0.3, -0.015 * p.y));
    };
    const Volume q = fieldVolume({36, 30, 34}, spacing, quadratic);
    const glm::dvec2 window(0.0, 4.0);
    for (Interpolation i : {Interpolation::CatmullRom, Interpolation::BSpline}) {
        const Fit fit = compareSlice(q, i, gradient, window, i == Interpolation::BSpline ? 12.0 : 2.5, true);
        std::printf("|grad| of a quadratic, %s: worst %.2e over %d points\n", interpolationName(i), fit.worst,
                    fit.compared);
        EXPECT_LE(fit.worst, 2e-4) << interpolationName(i);
        EXPECT_GT(fit.compared, 200);
    }
}

// beta3, the cubic B-spline's basis in closed form.
double beta3(double x) {
    x = std::abs(x);
    if (x < 1.0) return 2.0 / 3.0 - x * x + 0.5 * x * x * x;
    if (x < 2.0) return (2.0 - x) * (2.0 - x) * (2.0 - x) / 6.0;
    return 0.0;
}

// Catmull-Rom as the cardinal spline through p0..p3 at t in [0, 1).
double cardinal(const double p[4], double t) {
    return 0.5 * (2.0 * p[1] + (p[2] - p[0]) * t + (2.0 * p[0] - 5.0 * p[1] + 4.0 * p[2] - p[3]) * t * t +
                  (-p[0] + 3.0 * p[1] - 3.0 * p[2] + p[3]) * t * t * t);
}

// The CPU's cubic reconstruction at p: the voxels (Catmull-Rom, separably
// along x, y, z) or the coefficients `c` (B-spline, through beta3), indices
// clamped to the grid.
double cpuCubic(const Volume& v, const std::vector<float>* c, dvec3 p) {
    const glm::ivec3 d = v.dims();
    const auto at = [&](glm::ivec3 ijk) {
        ijk = glm::clamp(ijk, glm::ivec3(0), d - 1);
        return c ? double((*c)[std::size_t(ijk.x + d.x * (ijk.y + d.y * ijk.z))]) : v.value(ijk.x, ijk.y, ijk.z);
    };
    const dvec3 u = p / v.spacing() - 0.5, lower = glm::floor(u), t = u - lower;
    const glm::ivec3 i(lower);
    if (c) {
        double sum = 0.0;
        for (int z = -1; z <= 2; ++z)
            for (int y = -1; y <= 2; ++y)
                for (int x = -1; x <= 2; ++x)
                    sum += beta3(t.x - x) * beta3(t.y - y) * beta3(t.z - z) * at(i + glm::ivec3(x, y, z));
        return sum;
    }
    double planes[4];
    for (int z = 0; z < 4; ++z) {
        double rows[4];
        for (int y = 0; y < 4; ++y) {
            double line[4];
            for (int x = 0; x < 4; ++x) line[x] = at(i + glm::ivec3(x - 1, y - 1, z - 1));
            rows[y] = cardinal(line, t.x);
        }
        planes[z] = cardinal(rows, t.y);
    }
    return cardinal(planes, t.z);
}

TEST_F(Cubic, BothKernelsMatchCpuEvaluationAtRandomPoints) {
    std::mt19937 rng(1994);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    const Volume v = fieldVolume({13, 11, 9}, dvec3(1.3, 0.7, 2.1), [&](dvec3) { return uni(rng); });
    const std::vector<float> coefficients = bsplineCoefficients(v);
    const glm::dvec2 window(-3.0, 3.0);
    for (Interpolation i : {Interpolation::CatmullRom, Interpolation::BSpline}) {
        const std::vector<float>* c = i == Interpolation::BSpline ? &coefficients : nullptr;
        const Fit fit = compareSlice(v, i, [&](dvec3 p) { return cpuCubic(v, c, p); }, window, 0.0);
        std::printf("random volume, %s: worst %.2e over %d points\n", interpolationName(i), fit.worst, fit.compared);
        EXPECT_LE(fit.worst, 6.0 * 2e-5);
        EXPECT_GT(fit.compared, 1500);
    }
}

TEST_F(Cubic, TheBsplineInterpolatesEveryVoxelBordersIncluded) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(-50.0, 50.0);
    const Volume v = fieldVolume({9, 7, 8}, dvec3(1.0, 0.5, 0.5), [&](dvec3) { return uni(rng); });
    const std::vector<float> c = bsplineCoefficients(v);
    double worst = 0.0;
    for (int k = 0; k < 8; ++k)
        for (int j = 0; j < 7; ++j)
            for (int i = 0; i < 9; ++i)
                worst = std::max(worst, std::abs(cpuCubic(v, &c, (dvec3(i, j, k) + 0.5) * v.spacing()) - v.value(i, j, k)));
    EXPECT_LT(worst, 1e-4) << "on values of +-50 stored as float";
    // On the GPU: the view along x (9 voxels: the slicer's plane through the
    // centre is the middle layer's centres, i = 4), one pixel per voxel of
    // z (image right) and y (image down), so pixel centres sit on voxel centres.
    engine().setVolume(v);
    Scene s = sliceScene(Interpolation::BSpline, {-60.0, 60.0});
    s.camera = CameraSpec();
    s.camera.view = "+x";
    s.camera.projection = Projection::Orthographic;
    s.width = 8, s.height = 7;
    const Image image = engine().render(s);
    double gpuWorst = 0.0;
    int compared = 0;
    for (const SlicePoint& p : slicePoints(v, s)) {
        const dvec3 u = p.p / v.spacing() - 0.5;
        if (std::abs(u.y - std::round(u.y)) > 1e-3 || std::abs(u.z - std::round(u.z)) > 1e-3) continue;
        const double shown = -60.0 + 120.0 * double(image.at(p.x, p.y).r);
        gpuWorst = std::max(gpuWorst, std::abs(shown - v.value(4, int(std::round(u.y)), int(std::round(u.z)))));
        ++compared;
    }
    std::printf("B-spline at voxel centres: CPU %.2e, GPU %.2e over %d centres\n", worst, gpuWorst, compared);
    EXPECT_GT(compared, 20);
    EXPECT_LT(gpuWorst, 120.0 * 2e-5);
}

// The function check's reference outputs (Catmull-Rom values and gradients
// at random points of its volume; both kernels' weights) against the CPU.
TEST_F(Cubic, TheFunctionCheckReadsTheHandoutsKernels) {
    const nlohmann::json check = runFunctionCheck("cubic_random_points", "");
    const auto& volume = check.at("fixture").at("volume");
    const glm::ivec3 dims(volume["dims"][0], volume["dims"][1], volume["dims"][2]);
    const dvec3 extent(volume["extent"][0], volume["extent"][1], volume["extent"][2]);
    const double scale = volume["value_scale"], offset = volume["value_offset"];
    const Volume v = fieldVolume(dims, extent / dvec3(dims), [&](dvec3 p) {
        const glm::ivec3 ijk(glm::floor(p / (extent / dvec3(dims))));
        return double(volume["values"][std::size_t(ijk.x + dims.x * (ijk.y + dims.y * ijk.z))]) * scale + offset;
    });
    int values = 0, weights = 0, derivatives = 0;
    for (const auto& c : check.at("cases")) {
        const std::string f = c.at("function");
        const auto& in = c.at("input");
        if (f == "sample_cubic") {
            const dvec3 p(in["point"][0], in["point"][1], in["point"][2]);
            EXPECT_NEAR(c.at("output").get<double>(), cpuCubic(v, nullptr, p), 5e-5) << in.dump();
            ++values;
            continue;
        }
        if (f != "cubic_weights" && f != "cubic_derivative_weights") continue;
        const double t = in["t"];
        const bool bspline = in["kernel"] == "bspline (3)";
        // The weight of the value at offset k - 1 is the kernel at t - (k - 1).
        const auto weight = [&](int k, double at) {
            if (bspline) return beta3(at - (k - 1));
            double p[4] = {0, 0, 0, 0};
            p[k] = 1.0;
            return cardinal(p, at);
        };
        double sum = 0.0;
        for (int k = 0; k < 4; ++k) {
            const double h = 1e-4;
            const double expected = f == "cubic_weights" ? weight(k, t) : (weight(k, t + h) - weight(k, t - h)) / (2 * h);
            const double got = c.at("output")[std::size_t(k)];
            EXPECT_NEAR(got, expected, f == "cubic_weights" ? 1e-6 : 1e-5) << f << " " << in.dump() << " k=" << k;
            sum += got;
        }
        EXPECT_NEAR(sum, f == "cubic_weights" ? 1.0 : 0.0, 1e-5) << f << " " << in.dump();
        (f == "cubic_weights" ? weights : derivatives) += 1;
    }
    EXPECT_GT(values, 100);
    EXPECT_GT(weights, 40);
    EXPECT_GT(derivatives, 40);
}

// The Marschner-Lobb signal (phantoms.h, 41^3 on [-1, 1]^3) reconstructed
// by each interpolation and compared with the analytic function at the
// slicer's points: the figures of docs/reconstruction.md.
TEST_F(Cubic, MarschnerLobbErrorOfEachInterpolation) {
    const int n = 41;
    const Volume v = loadVolume("phantom:marschner-lobb:" + std::to_string(n));
    const auto analytic = [&](dvec3 p) {
        const dvec3 x = -1.0 + 2.0 * p / double(n);
        return marschnerLobbValue(x.x, x.y, x.z);
    };
    double rms[3] = {0, 0, 0}, worst[3] = {0, 0, 0};
    const Interpolation kinds[3] = {Interpolation::Trilinear, Interpolation::CatmullRom, Interpolation::BSpline};
    for (int k = 0; k < 3; ++k) {
        engine().setVolume(v);
        Scene scene = sliceScene(kinds[k], {-0.5, 1.5});
        scene.width = scene.height = 192;
        const Image image = engine().render(scene);
        int count = 0;
        for (const SlicePoint& s : slicePoints(v, scene)) {
            if (voxelsFromBorder(v, s.p) < 2.0) continue;
            const double e = -0.5 + 2.0 * double(image.at(s.x, s.y).r) - analytic(s.p);
            rms[k] += e * e, worst[k] = std::max(worst[k], std::abs(e));
            ++count;
        }
        rms[k] = std::sqrt(rms[k] / count);
        std::printf("Marschner-Lobb %d^3, %-11s RMS error %.4f, worst %.4f over %d points\n", n,
                    interpolationName(kinds[k]), rms[k], worst[k], count);
    }
    EXPECT_LT(rms[1], rms[0]) << "Catmull-Rom should beat trilinear on the Marschner-Lobb signal";
    EXPECT_LT(rms[2], rms[0]) << "the interpolating B-spline should beat trilinear";
}

}  // namespace
}  // namespace voxlab::testing
