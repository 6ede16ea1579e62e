// The transfer function on the GPU: a slicer render through a volume whose
// voxels sweep the whole 16-bit range must show, at every pixel, the
// piecewise-linear function of that voxel's value, within 1/255. The
// expected colour is interpolated here from the control points directly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "support/gl_fixture.h"

namespace voxlab::testing {
namespace {

// Piecewise-linear opacity, written for the test: clamp outside, linear
// between neighbouring points (values strictly increasing here).
double oracleAlpha(const std::vector<std::pair<double, double>>& pts, double v) {
    if (v <= pts.front().first) return pts.front().second;
    if (v >= pts.back().first) return pts.back().second;
    for (std::size_t i = 1; i < pts.size(); ++i)
        if (v <= pts[i].first) {
            const double t = (v - pts[i - 1].first) / (pts[i].first - pts[i - 1].first);
            return pts[i - 1].second + t * (pts[i].second - pts[i - 1].second);
        }
    return pts.back().second;
}

// n values evenly over [lo, hi].
std::vector<double> sweep(int n, double lo, double hi) {
    std::vector<double> out;
    for (int i = 0; i < n; ++i) out.push_back(lo + (hi - lo) * i / (n - 1));
    return out;
}

// A volume of values.size() x 2 x 2 voxels; voxel (i, *, *) holds values[i].
Volume sweepVolume(VoxelType type, const std::vector<double>& values) {
    const int n = int(values.size());
    std::vector<std::uint8_t> bytes(std::size_t(n) * 4 * voxelTypeSize(type));
    for (int k = 0; k < 4; ++k)
        for (int i = 0; i < n; ++i) {
            const double v = values[i];
            const std::size_t idx = std::size_t(k) * n + i;
            if (type == VoxelType::UInt16) {
                const std::uint16_t u = std::uint16_t(std::lround(v));
                std::memcpy(&bytes[idx * 2], &u, 2);
            } else {
                const float f = float(v);
                std::memcpy(&bytes[idx * 4], &f, 4);
            }
        }
    return Volume({n, 2, 2}, type, {1, 1, 1}, bytes, "sweep");
}

void checkSweep(const Volume& v, const std::vector<std::pair<double, double>>& pts) {
    std::vector<ControlPoint> cps;
    for (auto [value, alpha] : pts) cps.push_back({value, glm::vec3(1.0f), float(alpha)});
    Scene scene;
    scene.renderer = "slicer";
    scene.camera.view = "+z";
    scene.camera.projection = Projection::Orthographic;
    scene.width = v.dims().x, scene.height = 2;
    scene.interpolation = Interpolation::Nearest;
    scene.parameters["offset"] = -0.5;  // through the centres of layer 0
    scene.transferFunction = TransferFunction(cps);
    // White colour over black: the slicer shows exactly alpha.
    const std::vector<int> got = GlTest::renderGrey(v, scene);
    int bad = 0;
    std::string first;
    for (int i = 0; i < v.dims().x; ++i) {
        const double want = oracleAlpha(pts, v.value(i, 0, 0)) * 255.0;
        if (std::abs(got[i] - want) > 1.0 && bad++ == 0)
            first = "voxel " + std::to_string(i) + " value " + std::to_string(v.value(i, 0, 0)) + ": got " +
                    std::to_string(got[i]) + ", want " + std::to_string(want);
    }
    EXPECT_EQ(bad, 0) << first;
}

TEST_F(GlTest, SharpRampIn16BitDataMatchesThePiecewiseLinearFunction) {
    // The whole 16-bit range coarsely, and every integer around a ramp
    // 0 -> 1 over 3 units, followed by a gentle tail.
    std::vector<double> values = sweep(1024, 0, 65535);
    for (int x = 29990; x <= 30015; ++x) values.push_back(x);
    const Volume v = sweepVolume(VoxelType::UInt16, values);
    checkSweep(v, {{0, 0.0}, {30000.5, 0.0}, {30003.5, 1.0}, {40000, 0.2}, {65535, 0.9}});
}

TEST_F(GlTest, FloatValuesBetweenTableEntriesMatchThePiecewiseLinearFunction) {
    // 2000 float values around a narrow peak, off any table grid.
    std::vector<double> values = sweep(1000, -3.0, 17.0);
    for (double x : sweep(1000, 4.95, 5.05)) values.push_back(x);
    const Volume v = sweepVolume(VoxelType::Float32, values);
    checkSweep(v, {{-3, 0.1}, {4.9871, 0.1}, {5.0123, 1.0}, {5.0377, 0.0}, {17, 0.5}});
}

}  // namespace
}  // namespace voxlab::testing
