// Attenuated MIP with its depth cue (reference/attenuated_mip), against the
// handout's formula computed here on the CPU from the voxels each pixel's
// ray passes: orthographic axis views, nearest interpolation, one pixel per
// voxel (support/axis_columns.h). With lo, hi the volume's value range and
// f_m the m-th sample along the ray,
//     D_m = sum over k < m of (f_k - lo) / (hi - lo) * step_units
//     s_m = (m + 1/2) * step_units
//     I   = max over m of lo + (f_m - lo) exp(-attenuation D_m) exp(-depth_cue s_m)
// and the pixel shows (I - lo) / (hi - lo) (the window is the value range).
//
// The volume is isotropic with spacing 0.5 (so world units and units of the
// smallest spacing differ by a factor of 2) and float32 values on a grid of
// 1/4 (exact on the GPU), signed. At step 1 sample m sits at the centre of
// the m-th voxel of the column; at step 1/2 samples m = 2k, 2k + 1 sit a
// quarter voxel either side of voxel k's centre, never on a boundary, so
// nearest interpolation reads voxel k twice and the CPU knows every sample.
//
// Tolerance on the grey level: 1e-4. The GPU works in float (relative
// rounding 2^-24 = 6e-8 per operation). D_m is a sum of at most 44 terms
// of size <= 1/2, so it is off by at most 44 * 22 * 6e-8 = 6e-5, which
// the attenuation (0.3) turns into a relative error of 2e-5. GLSL allows
// exp() an error of (3 + 2|x|) ulp; here |x| <= 0.3 * 22 + 0.08 * 22 < 9,
// so 21 ulp = 1.3e-6 relative for each exp(). The dimmed height
// (f - lo) / (hi - lo) is at most 1, so the grey level is off by at most
// about 3e-5; 1e-4 leaves a factor of 3. Ignoring the depth cue changes
// the first sample alone by a factor exp(-0.04) (4%, 400 times the
// tolerance); the test checks that most pixels would show it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "support/axis_columns.h"
#include "support/gl_fixture.h"

namespace voxlab::testing {
namespace {

constexpr double kTolerance = 1e-4;

// A signed float32 volume (values -200..600 on a grid of 1/4, exact in
// float) from a fixed LCG, with a few bright slabs so that maxima lie at
// various depths; spacing 0.5 on every axis.
Volume syntheticVolume() {
    const glm::ivec3 d(18, 14, 22);
    std::vector<float> values(std::size_t(d.x) * d.y * d.z);
    std::uint32_t state = 2024;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i) {
                state = state * 1664525u + 1013904223u;
                const double u = double(state >> 8) / 16777216.0;  // [0, 1)
                const bool bright = (i + 2 * j + 3 * k) % 11 == 0;
                const double value = bright ? 300.0 + 300.0 * u : -200.0 + 400.0 * u * u;
                values[std::size_t((k * d.y + j) * d.x + i)] = float(std::round(value * 4.0) / 4.0);
            }
    std::vector<std::uint8_t> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return Volume(d, VoxelType::Float32, {0.5, 0.5, 0.5}, bytes, "attenuated-synthetic");
}

struct Setting {
    double attenuation, depthCue, step;  // step in units of the smallest spacing
};

// The handout's formula over one column of voxels (front to back); the
// column's voxels are `step` / spacing-units apart from sample to sample.
double cpuGrey(const std::vector<double>& column, glm::dvec2 range, const Setting& s) {
    const double lo = range.x, span = range.y - range.x;
    const int perVoxel = int(std::lround(1.0 / s.step));  // 1 or 2 samples per voxel
    const int n = int(column.size()) * perVoxel;
    double depth = 0.0, best = -1e300;
    for (int m = 0; m < n; ++m) {
        const double f = column[std::size_t(m / perVoxel)];
        const double dist = (m + 0.5) * s.step;
        best = std::max(best, lo + (f - lo) * std::exp(-s.attenuation * depth) * std::exp(-s.depthCue * dist));
        depth += (f - lo) / span * s.step;
    }
    return std::clamp((best - lo) / span, 0.0, 1.0);
}

// Renders one axis view and compares every pixel with the CPU; returns how
// many pixels the depth cue moves by more than 10 tolerances (so that a
// shader ignoring it could not pass).
int expectAxisView(const Volume& v, const AxisView& view, const Setting& s) {
    Scene scene = axisViewScene(v, view, "attenuated_mip");
    scene.step = s.step;
    scene.window = v.valueRange();
    scene.parameters["attenuation"] = s.attenuation;
    scene.parameters["depth_cue"] = s.depthCue;
    GlTest::engine().setVolume(v);
    const Image img = GlTest::engine().render(scene);
    const std::vector<PixelColumn> columns = axisColumns(v, view, scene.width, scene.height);
    int bad = 0, cued = 0;
    double worst = 0.0;
    std::string first;
    for (int py = 0; py < scene.height; ++py)
        for (int px = 0; px < scene.width; ++px) {
            const PixelColumn& col = columns[std::size_t(py) * scene.width + px];
            EXPECT_TRUE(col.inside && !col.ambiguous);  // pixel centres on voxel centres
            const double want = cpuGrey(col.values, v.valueRange(), s);
            const double without = cpuGrey(col.values, v.valueRange(), {s.attenuation, 0.0, s.step});
            if (std::abs(without - want) > 10 * kTolerance) ++cued;
            const double err = std::abs(double(img.at(px, py).r) - want);
            worst = std::max(worst, err);
            if (err > kTolerance && bad++ == 0) {
                std::ostringstream text;
                text << "pixel (" << px << ", " << py << "): got " << img.at(px, py).r << ", CPU gives " << want;
                first = text.str();
            }
        }
    EXPECT_EQ(bad, 0) << bad << " of " << scene.width * scene.height << " pixels off; first " << first;
    std::printf("view %s attenuation %g depth_cue %g step %g: largest error %.3g\n", view.name, s.attenuation,
                s.depthCue, s.step, worst);
    return cued * 2 > scene.width * scene.height ? 1 : 0;
}

class AttenuatedMipDepthCue : public GlTest {};

TEST_F(AttenuatedMipDepthCue, EveryAxisViewEqualsTheCpuFormula) {
    const Volume v = syntheticVolume();
    const Setting settings[] = {
        {0.0, 0.08, 1.0},   // the depth cue alone
        {0.3, 0.05, 1.0},   // both together
        {0.3, 0.05, 0.5},   // both, two samples per voxel: step_units 1/2
        {0.3, 0.0, 1.0},    // the attenuation alone, as before the depth cue
    };
    for (const Setting& s : settings) {
        int viewsWithCue = 0;
        for (const AxisView& view : kAxisViews) {
            SCOPED_TRACE(std::string("view ") + view.name);
            viewsWithCue += expectAxisView(v, view, s);
        }
        // The depth cue moves most pixels of every view, so ignoring it fails.
        if (s.depthCue > 0) {
            EXPECT_EQ(viewsWithCue, int(std::size(kAxisViews)));
        }
    }
}

// The depth cue is per unit length, not per sample: halving the step leaves
// the image nearly unchanged (the column is the same voxel read twice, so
// only the sum D_m and where the maximum is taken differ by a step), while
// a cue per sample would dim twice as fast.
TEST_F(AttenuatedMipDepthCue, TheDepthCueDoesNotDependOnTheStep) {
    const Volume v = syntheticVolume();
    for (const AxisView& view : kAxisViews) {
        SCOPED_TRACE(std::string("view ") + view.name);
        Scene scene = axisViewScene(v, view, "attenuated_mip");
        scene.window = v.valueRange();
        scene.parameters["attenuation"] = 0.0;
        scene.parameters["depth_cue"] = 0.08;
        GlTest::engine().setVolume(v);
        const Image coarse = GlTest::engine().render(scene);
        scene.step = 0.5;
        const Image fine = GlTest::engine().render(scene);
        // Without attenuation, the brightest voxel of a column is read at
        // depths (k + 1/2) and (k + 1/4) voxels: a factor exp(0.08 / 4),
        // 2%, on the height above lo, at most 0.02 in grey.
        for (int py = 0; py < scene.height; ++py)
            for (int px = 0; px < scene.width; ++px)
                ASSERT_NEAR(coarse.at(px, py).r, fine.at(px, py).r, 0.021) << "pixel " << px << ", " << py;
    }
}

}  // namespace
}  // namespace voxlab::testing
