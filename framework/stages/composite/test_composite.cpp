// The "composite" renderer (direct volume rendering with the 1D transfer
// function) against CPU compositing written here from the README's
// conventions:
//  - a sample classified by the piecewise-linear transfer function has
//    colour c and opacity per unit length alpha; with a step of s unit
//    lengths its opacity is a = 1 - (1 - alpha)^s;
//  - front to back: C += (1 - A) a c, A += (1 - A) a, stopping once
//    A >= early_termination; the pixel is C + (1 - A) * background.
// Axis-aligned orthographic renders with nearest interpolation and step 1
// see exactly the voxel columns of tests/support/axis_columns.h, so real
// datasets with their presets can be composited on the CPU voxel by voxel.
// The other properties (step-size independence, back to front, pre-
// classification, jitter, the fallback ramp) are checked on their own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "support/axis_columns.h"
#include "support/cpu_tf.h"
#include "support/gl_fixture.h"

namespace voxlab::testing {
namespace {

// ---------------------------------------------------------------------------
// CPU oracle pieces.

// cpuTransferFunction() memoised for integer-valued volumes (every voxel value is an
// integer in [lo, hi]), so that 256^3 columns stay cheap.
class Classifier {
public:
    Classifier(std::vector<ControlPoint> pts, const Volume& v) : pts_(std::move(pts)) {
        if (v.type() != VoxelType::Float32) {
            lo_ = v.minValue();
            for (double x = v.minValue(); x <= v.maxValue(); x += 1.0) table_.push_back(cpuTransferFunction(pts_, x));
        }
    }
    glm::dvec4 operator()(double v) const {
        if (!table_.empty()) return table_[std::size_t(v - lo_)];
        return cpuTransferFunction(pts_, v);
    }

private:
    std::vector<ControlPoint> pts_;
    double lo_ = 0.0;
    std::vector<glm::dvec4> table_;
};

// Front-to-back compositing of samples given as (rgb, opacity of the sample
// already corrected for the step), with early termination exactly as the
// README defines it. Returns premultiplied colour and opacity.
glm::dvec4 compositeFrontToBack(const std::vector<glm::dvec4>& samples, double earlyTermination) {
    glm::dvec3 c(0.0);
    double a = 0.0;
    for (const glm::dvec4& s : samples) {
        c += (1.0 - a) * s.a * glm::dvec3(s);
        a += (1.0 - a) * s.a;
        if (a >= earlyTermination) break;
    }
    return {c, a};
}

glm::dvec3 overBackground(const glm::dvec4& premultiplied, glm::dvec3 background) {
    return glm::dvec3(premultiplied) + (1.0 - premultiplied.a) * background;
}

// A float volume from a function of the voxel index.
template <class F>
Volume floatVolume(glm::ivec3 d, F f, glm::dvec3 spacing = glm::dvec3(1.0)) {
    std::vector<std::uint8_t> bytes(std::size_t(d.x) * d.y * d.z * 4);
    std::size_t idx = 0;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i, ++idx) {
                const float x = float(f(i, j, k));
                std::memcpy(&bytes[idx * 4], &x, 4);
            }
    return Volume(d, VoxelType::Float32, spacing, bytes, "test");
}

TransferFunction preset(const std::string& name) { return TransferFunction::load(datasetPath("tf/" + name)); }

// Largest and mean absolute difference over the rgb channels of two images.
struct Difference {
    double max = 0.0, mean = 0.0, signedMean = 0.0;
    int differing = 0;  // pixels with any channel apart by more than 1e-4
};

Difference compare(const Image& a, const Image& b) {
    Difference d;
    double sum = 0.0, signedSum = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            bool differs = false;
            for (int ch = 0; ch < 3; ++ch) {
                const double e = double(a.at(x, y)[ch]) - double(b.at(x, y)[ch]);
                d.max = std::max(d.max, std::abs(e));
                sum += std::abs(e);
                signedSum += e;
                differs = differs || std::abs(e) > 1e-4;
            }
            d.differing += differs;
        }
    const double n = 3.0 * a.width * a.height;
    d.mean = sum / n;
    d.signedMean = signedSum / n;
    return d;
}

// An orbit camera (perspective) looking at the whole box.
Scene orbitScene(const char* renderer, int size) {
    Scene scene;
    scene.renderer = renderer;
    scene.camera.view = "";
    scene.camera.azimuth = 35.0;
    scene.camera.elevation = 25.0;
    scene.camera.projection = Projection::Perspective;
    scene.width = scene.height = size;
    scene.interpolation = Interpolation::Trilinear;
    scene.step = 1.0;
    return scene;
}

// ---------------------------------------------------------------------------
// Axis views of real datasets against CPU compositing over voxel columns.

struct AxisCase {
    std::string dataset, preset;
    std::vector<std::string> views;
    glm::vec3 background;
};

void PrintTo(const AxisCase& c, std::ostream* os) { *os << c.dataset; }

class CompositeAxisViews : public GlTest, public ::testing::WithParamInterface<AxisCase> {};

// Tolerance 2/255 per channel (float image, unrounded): the GPU reads the
// transfer function from a baked table accurate to 0.5/255 in colour and
// opacity; over a column those errors add up in weighted form (the colour
// part is bounded by 0.5/255 since sum T a <= 1, the opacity part slightly
// more), and near the early-termination threshold GPU float and CPU double
// may stop one sample apart, which changes the pixel by at most
// (1 - 0.99) * a * c. Measured: 0 on the uint8 data (their tables hold the
// function exactly at integers), 1.4/255 on cthead (a table cell past the
// 1050 bend is not quite transparent, and rays cross ~100 soft-tissue
// samples there), 0.4/255 on headsq.
TEST_P(CompositeAxisViews, AxisViewEqualsCpuFrontToBackCompositing) {
    const AxisCase& param = GetParam();
    const Volume v = loadVolume(datasetPath(param.dataset));
    const TransferFunction tf = preset(param.preset);
    const Classifier classify(tf.points(), v);
    const double minSpacing = v.minSpacing();
    for (const AxisView& view : kAxisViews) {
        if (std::find(param.views.begin(), param.views.end(), view.name) == param.views.end()) continue;
        SCOPED_TRACE(std::string("view ") + view.name);
        Scene scene = axisViewScene(v, view, "composite");
        scene.transferFunction = tf;
        scene.background = param.background;
        engine().setVolume(v);
        const Image img = engine().render(scene);
        const std::vector<PixelColumn> cols = axisColumns(v, view, scene.width, scene.height);

        // Step 1 is one smallest spacing; along an axis of coarser spacing
        // sample m, at depth (m + 1/2) * minSpacing, lies in voxel
        // floor(depth / spacing) of the column (the same voxel may be
        // sampled more than once). The ray through the box has length
        // N * spacing, so n = floor(N * spacing / minSpacing + 1/2).
        const double sf = v.spacing()[view.fwdAxis];
        const int nVoxels = v.dims()[view.fwdAxis];
        const int n = int(std::floor(nVoxels * sf / minSpacing + 0.5));
        std::vector<int> voxelOfSample;
        for (int m = 0; m < n; ++m) {
            const double u = (m + 0.5) * minSpacing / sf;
            ASSERT_GT(std::abs(u - std::round(u)), 1e-3) << "sample on a voxel boundary";
            voxelOfSample.push_back(std::min(int(std::floor(u)), nVoxels - 1));
        }

        const glm::dvec3 bg(param.background);
        int bad = 0, checked = 0, ambiguous = 0;
        double worst = 0.0;
        std::string first;
        for (int py = 0; py < scene.height; ++py)
            for (int px = 0; px < scene.width; ++px) {
                const PixelColumn& col = cols[std::size_t(py) * scene.width + px];
                if (col.ambiguous) {
                    ++ambiguous;
                    continue;
                }
                glm::dvec3 want = bg;
                if (col.inside) {
                    std::vector<glm::dvec4> samples;
                    for (int m : voxelOfSample) samples.push_back(classify(col.values[m]));  // step 1: a = alpha
                    want = overBackground(compositeFrontToBack(samples, 0.99), bg);
                }
                const glm::vec4 got = img.at(px, py);
                ++checked;
                for (int ch = 0; ch < 3; ++ch) {
                    const double e = std::abs(got[ch] - want[ch]);
                    worst = std::max(worst, e);
                    if (e > 2.0 / 255.0 && bad++ == 0) {
                        std::ostringstream os;
                        os << "pixel (" << px << ", " << py << ") channel " << ch << ": got " << got[ch]
                           << ", CPU compositing gives " << want[ch];
                        first = os.str();
                    }
                }
            }
        EXPECT_EQ(bad, 0) << first << " (worst " << worst * 255 << "/255)";
        EXPECT_LT(ambiguous, checked / 20);
        // The preset must show something: the test would be vacuous on an
        // image of background only.
        int shown = 0;
        for (int py = 0; py < scene.height; ++py)
            for (int px = 0; px < scene.width; ++px)
                shown += glm::length(glm::dvec3(img.at(px, py)) - bg) > 0.05;
        EXPECT_GT(shown, scene.width * scene.height / 20);
    }
}

const glm::vec3 kBlack(0.0f), kBlue(0.1f, 0.2f, 0.45f), kGrey(0.5f);

INSTANTIATE_TEST_SUITE_P(
    RealDatasetsWithPresets, CompositeAxisViews,
    ::testing::Values(
        // 256^3 uint8: the two views along z are enough to cover its size.
        AxisCase{"bonsai.nrrd", "bonsai.json", {"+z", "-x"}, kBlack},
        AxisCase{"tooth.nrrd", "tooth.json", {"+z", "-z", "+x", "-x", "+y", "-y"}, kBlack},
        // uint16, spacing 1 1 2: along z every voxel is sampled twice.
        AxisCase{"cthead.nrrd", "cthead.json", {"+z", "-x", "+y"}, kBlue},
        // int16, spacing 3.2 3.2 1.5: along x and y each step of 1.5 falls
        // in a 3.2-wide voxel, two or three samples per voxel.
        AxisCase{"headsq.nrrd", "headsq.json", {"+z", "-z", "+x", "-y"}, kBlack},
        AxisCase{"fuel.nrrd", "fuel.json", {"+z", "-z", "+x", "-x", "+y", "-y"}, kGrey},
        AxisCase{"neghip.nrrd", "neghip.json", {"+z", "-z", "+x", "-x", "+y", "-y"}, kBlack}),
    [](const auto& info) {
        std::string s = info.param.dataset.substr(0, info.param.dataset.find('.'));
        return s;
    });

// ---------------------------------------------------------------------------
// Constant density: the closed form of the emission-absorption integral.

// A white transfer function of constant opacity a over a volume of ones
// (values 0 and 1 map to alpha 0 and a: the table holds both exactly).
TransferFunction whiteRamp(double a) {
    return TransferFunction({{0.0, glm::vec3(1.0f), 0.0f}, {1.0, glm::vec3(1.0f), float(a)}});
}

// A box of ones in a volume of zeros: column x has the box from z = 3 to
// z = 3 + thickness(x) - 1, so with nearest interpolation and step 1 the
// ray through column x meets thickness(x) samples of opacity a and zeros
// (opacity 0) elsewhere: the pixel is 1 - (1 - a)^n over black.
// Tolerance 1e-4: float arithmetic only (the table entries at 0 and 1 are exact).
TEST_F(GlTest, SlabOfConstantDensityGivesOneMinusTransmittanceToTheN) {
    const int width = 12;
    const auto thickness = [](int i) { return i == 0 ? 0 : 1 + (i * 5) % 14; };  // 0, 6, 11, 2, ...
    const Volume v = floatVolume({width, 3, 20}, [&](int i, int, int k) {
        return k >= 3 && k < 3 + thickness(i) ? 1.0 : 0.0;
    });
    for (double a : {0.05, 0.3, 0.8}) {
        SCOPED_TRACE("alpha " + std::to_string(a));
        Scene scene = axisViewScene(v, kAxisViews[0], "composite");  // +z
        scene.transferFunction = whiteRamp(a);
        scene.parameters["early_termination"] = 1.0;
        engine().setVolume(v);
        const Image img = engine().render(scene);
        for (int i = 0; i < width; ++i) {
            const double want = 1.0 - std::pow(1.0 - a, thickness(i));
            for (int j = 0; j < 3; ++j)
                for (int ch = 0; ch < 3; ++ch)
                    EXPECT_NEAR(img.at(i, j)[ch], want, 1e-4) << "column " << i << " (n = " << thickness(i) << ")";
        }
    }
}

// A constant volume D voxels deep sampled with a non-integer step s: the ray
// takes n = floor(D / s + 1/2) samples, each of opacity 1 - (1 - a)^s, so the
// pixel is 1 - (1 - a)^(n s): the opacity of the length the samples cover.
// Without the correction it would be 1 - (1 - a)^n, far off for s != 1.
// Tolerance 1e-4: float arithmetic (pow) only.
TEST_F(GlTest, NonIntegerStepIsOpacityCorrected) {
    const double a = 0.12;
    for (int depth : {3, 10, 25})
        for (double step : {0.3, 0.7, 1.6, 2.5}) {
            SCOPED_TRACE("depth " + std::to_string(depth) + ", step " + std::to_string(step));
            const Volume v = floatVolume({4, 4, depth}, [](int, int, int) { return 1.0; });
            Scene scene = axisViewScene(v, kAxisViews[1], "composite");  // -z
            scene.transferFunction = whiteRamp(a);
            scene.parameters["early_termination"] = 1.0;
            scene.step = step;
            engine().setVolume(v);
            const Image img = engine().render(scene);
            const int n = int(std::floor(depth / step + 0.5));
            const double want = 1.0 - std::pow(1.0 - a, n * step);
            for (int y = 0; y < 4; ++y)
                for (int x = 0; x < 4; ++x) EXPECT_NEAR(img.at(x, y).g, want, 1e-4) << "n = " << n;
        }
}

// Early termination as defined: stop after the first sample that brings A
// to the threshold or above. With a = 0.5 per sample A runs 0.5, 0.75,
// 0.875, 0.9375, ...; a red slab behind the first samples shows only if the
// ray gets that far. Tolerance 1e-4: float arithmetic.
TEST_F(GlTest, EarlyTerminationStopsOnceOpacityReachesTheThreshold) {
    // Values 1 (white) for the first 4 voxels along +z, then 2 (red).
    const Volume v = floatVolume({2, 2, 12}, [](int, int, int k) { return k < 4 ? 1.0 : 2.0; });
    const TransferFunction tf({{1.0, glm::vec3(1.0f), 0.5f}, {2.0, glm::vec3(1.0f, 0.0f, 0.0f), 0.5f}});
    struct Case {
        double threshold;
        int samples;  // how many samples the CPU rule composites
    };
    for (Case c : {Case{0.5, 1}, Case{0.75, 2}, Case{0.9, 4}, Case{0.95, 5}, Case{0.99, 7}, Case{1.0, 12}}) {
        SCOPED_TRACE("threshold " + std::to_string(c.threshold));
        Scene scene = axisViewScene(v, kAxisViews[0], "composite");
        scene.transferFunction = tf;
        scene.parameters["early_termination"] = c.threshold;
        scene.background = glm::vec3(0.0f, 0.0f, 1.0f);
        engine().setVolume(v);
        const glm::vec4 got = engine().render(scene).at(1, 1);
        std::vector<glm::dvec4> samples;
        for (int k = 0; k < 12; ++k) samples.push_back(k < 4 ? glm::dvec4(1, 1, 1, 0.5) : glm::dvec4(1, 0, 0, 0.5));
        const glm::dvec4 acc = compositeFrontToBack(samples, c.threshold);
        const glm::dvec3 want = overBackground(acc, glm::dvec3(0, 0, 1));
        // The rule itself, restated: A = 1 - 0.5^samples.
        EXPECT_NEAR(acc.a, 1.0 - std::pow(0.5, c.samples), 1e-12);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch], want[ch], 1e-4) << "channel " << ch;
    }
}

// ---------------------------------------------------------------------------
// Properties of the compositing loop.

// Back to front (which never stops early) gives the same image as front to
// back without early termination: the two recurrences expand to the same
// sum. Tolerance 1/255; in practice only float rounding separates them.
TEST_F(GlTest, BackToFrontEqualsFrontToBackWithoutEarlyTermination) {
    const Volume v = loadVolume(datasetPath("neghip.nrrd"));
    Scene scene = orbitScene("composite", 96);
    scene.transferFunction = preset("neghip.json");
    scene.step = 0.5;
    scene.background = glm::vec3(0.3f, 0.1f, 0.2f);
    scene.parameters["early_termination"] = 1.0;
    engine().setVolume(v);
    const Image front = engine().render(scene);
    scene.parameters["back_to_front"] = 1.0;
    const Image back = engine().render(scene);
    const Difference d = compare(front, back);
    EXPECT_LE(d.max, 1.0 / 255.0);
    // Not vacuous: the image shows the volume (and differs from the
    // default early termination at 0.99 only where A nears 1).
    EXPECT_GT(compare(front, Image(96, 96)).mean, 0.02);
}

// Halving the step with opacity correction approximates the same
// emission-absorption integral: both images are Riemann sums of it (midpoint
// samples of the trilinear field, each standing for its step), which differ
// by O(step) where the field is smooth. Tooth with its preset, an orbit view
// with trilinear interpolation, step 1 against step 0.5, over the pixels
// where the tooth shows. Measured (printed below): max 3.8/255, mean
// 0.24/255. Bounds: mean < 1/255 (the O(step) term averages out over
// smooth regions; only thin sharp layers, which the coarser step straddles,
// differ by more than a grey level) and max < 12/255 (those layers, at a
// sharp preset ramp).
// The same render without correction, which is what step 0.5 would give if
// opacity were not corrected (each sample keeping the full alpha of a unit
// length: the TF's alphas replaced by 1 - (1 - alpha)^2, which the
// correction at step 0.5 turns back into alpha), is far off: its mean
// difference must exceed both 4/255 and 10 times the corrected one
// (measured: 12.8/255, about 50 times).
TEST_F(GlTest, HalvingTheStepWithOpacityCorrectionKeepsTheImage) {
    const Volume v = loadVolume(datasetPath("tooth.nrrd"));
    const TransferFunction tf = preset("tooth.json");
    const int size = 96;
    Scene scene = orbitScene("composite", size);
    scene.transferFunction = tf;
    engine().setVolume(v);
    scene.step = 1.0;
    const Image coarse = engine().render(scene);
    scene.step = 0.5;
    const Image fine = engine().render(scene);
    std::vector<ControlPoint> doubled = tf.points();
    for (ControlPoint& p : doubled) p.alpha = float(1.0 - (1.0 - p.alpha) * (1.0 - p.alpha));
    scene.transferFunction = TransferFunction(doubled);
    const Image uncorrected = engine().render(scene);

    // Max and mean over the channels of the pixels where the tooth shows.
    const auto difference = [&](const Image& a, const Image& b) {
        double max = 0.0, sum = 0.0;
        int count = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::vec4 p = a.at(x, y), q = b.at(x, y);
                if (p.r + p.g + p.b < 0.02f && q.r + q.g + q.b < 0.02f) continue;
                for (int ch = 0; ch < 3; ++ch) {
                    max = std::max(max, double(std::abs(p[ch] - q[ch])));
                    sum += std::abs(p[ch] - q[ch]);
                    ++count;
                }
            }
        return std::make_pair(max, count ? sum / count : 0.0);
    };
    const auto [maxCorrected, meanCorrected] = difference(coarse, fine);
    const auto [maxWrong, meanWrong] = difference(coarse, uncorrected);
    std::printf("[ measured ] step 1 vs 0.5, corrected: max %.2f/255, mean %.3f/255; "
                "uncorrected: max %.2f/255, mean %.3f/255\n",
                maxCorrected * 255, meanCorrected * 255, maxWrong * 255, meanWrong * 255);
    EXPECT_LT(meanCorrected, 1.0 / 255.0);
    EXPECT_LT(maxCorrected, 12.0 / 255.0);
    EXPECT_GT(meanWrong, 4.0 / 255.0);
    EXPECT_GT(meanWrong, 10.0 * meanCorrected);
}

// ---------------------------------------------------------------------------
// Pre-classification.

// With nearest interpolation pre-classification classifies the one voxel
// that contains the sample, exactly what post-classification does.
// Tolerance: equal up to float noise (1e-6).
TEST_F(GlTest, PreclassificationWithNearestEqualsPostclassification) {
    const Volume v = loadVolume(datasetPath("tooth.nrrd"));
    Scene scene = orbitScene("composite", 80);
    scene.interpolation = Interpolation::Nearest;
    scene.transferFunction = preset("tooth.json");
    scene.step = 0.7;
    engine().setVolume(v);
    const Image post = engine().render(scene);
    scene.parameters["preclassify"] = 1.0;
    const Image pre = engine().render(scene);
    EXPECT_LE(compare(post, pre).max, 1e-6);
    EXPECT_GT(compare(post, Image(80, 80)).mean, 0.02);
}

// With trilinear interpolation, step 1 along an axis with pixel centres on
// voxel centres, every sample sits on a voxel centre: one voxel has all the
// weight, so pre- and post-classification both give the voxel's own
// classification and the image equals CPU compositing over the voxels.
// Tolerances: pre vs post 1/255 (the weights are 1 and 0 only up to float
// rounding of the sample position); against the CPU 2/255 as for the axis
// views above.
TEST_F(GlTest, PreclassificationAtVoxelCentresEqualsPostAndCpu) {
    const Volume v = loadVolume(datasetPath("neghip.nrrd"));
    const TransferFunction tf = preset("neghip.json");
    const Classifier classify(tf.points(), v);
    const AxisView& view = kAxisViews[3];  // -x
    Scene scene = axisViewScene(v, view, "composite");
    scene.interpolation = Interpolation::Trilinear;
    scene.transferFunction = tf;
    engine().setVolume(v);
    const Image post = engine().render(scene);
    scene.parameters["preclassify"] = 1.0;
    const Image pre = engine().render(scene);
    EXPECT_LE(compare(post, pre).max, 1.0 / 255.0);
    const std::vector<PixelColumn> cols = axisColumns(v, view, scene.width, scene.height);
    int bad = 0;
    for (int py = 0; py < scene.height; ++py)
        for (int px = 0; px < scene.width; ++px) {
            const PixelColumn& col = cols[std::size_t(py) * scene.width + px];
            ASSERT_TRUE(col.inside && !col.ambiguous);
            std::vector<glm::dvec4> samples;
            for (double x : col.values) samples.push_back(classify(x));
            const glm::dvec4 want = compositeFrontToBack(samples, 0.99);
            for (int ch = 0; ch < 3; ++ch) bad += std::abs(pre.at(px, py)[ch] - want[ch]) > 2.0 / 255.0;
        }
    EXPECT_EQ(bad, 0);
}

// Between voxels: two voxels along x, red and nearly opaque (value 0, alpha
// 0.9) and green and faint (value 1, alpha 0.05). Pre-classification at a
// point with weight t on the green voxel gives (Wittenbrink et al.)
//     alpha = (1-t) 0.9 + t 0.05,
//     colour = ((1-t) 0.9 red + t 0.05 green) / alpha,
// not the plain mix of red and green, which lets the transparent green
// bleed into the red. The volume is 2 voxels deep along z, so each ray takes
// two samples of that classification (constant along z) and
//     A = 1 - (1 - alpha)^2, C = colour * A.
// Rendering over black and over white gives C and A separately
// (white - black = 1 - A). Tolerance 1e-3: float arithmetic, and the
// transfer-function table holds both control points exactly (they are its
// end entries).
TEST_F(GlTest, PreclassificationBetweenVoxelsWeightsColoursByOpacity) {
    const Volume v = floatVolume({2, 1, 2}, [](int i, int, int) { return double(i); });
    Scene scene;
    scene.renderer = "composite";
    scene.camera.view = "+z";
    scene.camera.projection = Projection::Orthographic;
    scene.width = 64, scene.height = 32;  // 32 pixels per unit length
    scene.interpolation = Interpolation::Trilinear;
    scene.step = 1.0;
    scene.transferFunction =
        TransferFunction({{0.0, glm::vec3(1.0f, 0.0f, 0.0f), 0.9f}, {1.0, glm::vec3(0.0f, 1.0f, 0.0f), 0.05f}});
    scene.parameters["preclassify"] = 1.0;
    scene.parameters["early_termination"] = 1.0;
    engine().setVolume(v);
    const Image black = engine().render(scene);
    scene.background = glm::vec3(1.0f);
    const Image white = engine().render(scene);
    int inBetween = 0;
    for (int px = 0; px < 64; ++px) {
        // Pixel centre x = (px + 1/2) / 32; voxel centres at 0.5 and 1.5,
        // clamped to the grid outside them.
        const double t = std::clamp((px + 0.5) / 32.0 - 0.5, 0.0, 1.0);
        inBetween += t > 0.0 && t < 1.0;
        const double alpha = (1 - t) * 0.9 + t * 0.05;
        const glm::dvec3 colour = ((1 - t) * 0.9 * glm::dvec3(1, 0, 0) + t * 0.05 * glm::dvec3(0, 1, 0)) / alpha;
        const double A = 1.0 - (1.0 - alpha) * (1.0 - alpha);
        const int py = 16;
        const double gotA = 1.0 - (white.at(px, py).b - black.at(px, py).b);
        EXPECT_NEAR(gotA, A, 1e-3) << "pixel " << px << " t = " << t;
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(black.at(px, py)[ch], colour[ch] * A, 1e-3)
                << "pixel " << px << " t = " << t << " channel " << ch;
    }
    EXPECT_GE(inBetween, 30);
}

// ---------------------------------------------------------------------------
// Jitter.

// Jitter moves each ray's first sample by a pixel-dependent fraction of a
// step: the image changes in most pixels, but the samples still cover the
// same integral, so the mean brightness stays put (bound 1/255 on the
// signed mean, 3/255 on the mean absolute change: measured well below).
// The offset is a hash of the pixel, so two renders are identical.
TEST_F(GlTest, JitterChangesPixelsButNotTheMeanAndIsDeterministic) {
    const Volume v = loadVolume(datasetPath("bonsai.nrrd"));
    Scene scene = orbitScene("composite", 96);
    scene.transferFunction = preset("bonsai.json");
    scene.step = 1.0;
    engine().setVolume(v);
    const Image plain = engine().render(scene);
    scene.parameters["jitter"] = 1.0;
    const Image jittered = engine().render(scene);
    const Image again = engine().render(scene);
    EXPECT_EQ(jittered.rgba, again.rgba);
    const Difference d = compare(plain, jittered);
    int covered = 0;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) covered += plain.at(x, y).r + plain.at(x, y).g + plain.at(x, y).b > 0.02f;
    std::printf("[ measured ] jitter: %d of %d visible pixels differ, signed mean %.3f/255, mean |diff| %.3f/255\n",
                d.differing, covered, d.signedMean * 255, d.mean * 255);
    EXPECT_GT(d.differing, covered / 2);
    EXPECT_LT(std::abs(d.signedMean), 1.0 / 255.0);
    EXPECT_LT(d.mean, 3.0 / 255.0);
}

// How far jitter moves the start, read through a constant volume 10 voxels
// deep at step 0.75 (orthographic +z, 32 x 32 rays): a ray that starts
// delta steps late takes n = floor(10 / 0.75 - delta + 1/2) samples of
// opacity 1 - (1 - a)^0.75 each, and its pixel is 1 - (1 - a)^(0.75 n), so
// n can be read back per pixel. Unjittered, n = 13 everywhere. With delta
// uniform in [-1/2, 1/2) (a fraction of one step, centred), n is 14 where
// delta < -1/6, a third of the rays, and 13 elsewhere; never anything else.
// Bounds on that third: [0.2, 0.47] (1024 rays: a few standard deviations).
TEST_F(GlTest, JitterOffsetsTheStartByLessThanAStep) {
    const double a = 0.1, step = 0.75;
    const Volume v = floatVolume({32, 32, 10}, [](int, int, int) { return 1.0; });
    Scene scene = axisViewScene(v, kAxisViews[0], "composite");
    scene.transferFunction = whiteRamp(a);
    scene.parameters["early_termination"] = 1.0;
    scene.step = step;
    engine().setVolume(v);
    for (bool jitter : {false, true}) {
        scene.parameters["jitter"] = jitter ? 1.0 : 0.0;
        const Image img = engine().render(scene);
        int counts[2] = {0, 0}, other = 0;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const double n = std::log(1.0 - img.at(x, y).r) / (step * std::log(1.0 - a));
                const long rounded = std::lround(n);
                ASSERT_NEAR(n, double(rounded), 1e-3) << "pixel (" << x << ", " << y << ")";  // whole samples
                if (rounded == 13 || rounded == 14) ++counts[rounded - 13];
                else ++other;
            }
        EXPECT_EQ(other, 0) << "sample counts other than 13 or 14" << (jitter ? " with jitter" : "");
        if (!jitter) {
            EXPECT_EQ(counts[1], 0);
        } else {
            const double third = counts[1] / 1024.0;
            std::printf("[ measured ] jitter: %.3f of the rays take 14 samples (uniform offset: 1/3)\n", third);
            EXPECT_GE(third, 0.2);
            EXPECT_LE(third, 0.47);
        }
    }
}

// ---------------------------------------------------------------------------
// No transfer function: the fallback ramp of render_engine.h, white, opacity
// 0 at window.lo rising linearly to 0.1 per unit length at window.hi,
// clamped outside. Checked like the axis views (tolerance 2/255, same
// reasons), with the default window (the data range) and an explicit one.
TEST_F(GlTest, NoTransferFunctionUsesTheGreyRampOverTheWindow) {
    const Volume v = loadVolume(datasetPath("tooth.nrrd"));
    for (std::optional<glm::dvec2> window : {std::optional<glm::dvec2>(), std::optional(glm::dvec2(120.0, 200.0))}) {
        const glm::dvec2 w = window.value_or(glm::dvec2(v.minValue(), v.maxValue()));
        SCOPED_TRACE("window " + std::to_string(w.x) + ".." + std::to_string(w.y));
        const std::vector<ControlPoint> ramp = {{w.x, glm::vec3(1.0f), 0.0f}, {w.y, glm::vec3(1.0f), 0.1f}};
        const Classifier classify(ramp, v);
        for (const AxisView& view : {kAxisViews[0], kAxisViews[4]}) {
            Scene scene = axisViewScene(v, view, "composite");
            scene.window = window;
            engine().setVolume(v);
            const Image img = engine().render(scene);
            const std::vector<PixelColumn> cols = axisColumns(v, view, scene.width, scene.height);
            int bad = 0;
            double sum = 0.0;
            for (int py = 0; py < scene.height; ++py)
                for (int px = 0; px < scene.width; ++px) {
                    const PixelColumn& col = cols[std::size_t(py) * scene.width + px];
                    std::vector<glm::dvec4> samples;
                    for (double x : col.values) samples.push_back(classify(x));
                    const double want = compositeFrontToBack(samples, 0.99).a;  // white: C = A
                    sum += want;
                    bad += std::abs(img.at(px, py).r - want) > 2.0 / 255.0;
                }
            EXPECT_EQ(bad, 0) << "view " << view.name;
            EXPECT_GT(sum / (scene.width * scene.height), 0.05);  // not an empty image
        }
    }
}

// ---------------------------------------------------------------------------
// Shading (off by default): a white Phong headlight on linear ramps, where
// the lit colour is known in closed form. The gradient is exact on a linear
// field (central differences, one-sided at the faces).
//  - ramp along x, viewed along +z: the normal is perpendicular to the view
//    and to the headlight, so diffuse and specular vanish: colour ka * c;
//  - ramp along z, viewed along +z: the normal faces the viewer (two-sided),
//    n.l = 1 and r.v = 1: colour (ka + kd) c + ks.
// Each sample gets the same lit colour L and opacity a (constant TF), so
// the pixel is L (1 - (1 - a)^n). Tolerance 1e-3: float arithmetic.
TEST_F(GlTest, ShadingWithAHeadlightOnLinearRamps) {
    const double a = 0.2, ka = 0.25, kd = 0.6, ks = 0.1;
    const glm::dvec3 c(0.8, 0.5, 0.3);
    const TransferFunction tf({{0.0, glm::vec3(c), float(a)}});
    for (int axis : {0, 2}) {
        const Volume v = floatVolume({6, 6, 6}, [&](int i, int, int k) { return 3.0 * (axis == 0 ? i : k); });
        Scene scene = axisViewScene(v, kAxisViews[0], "composite");
        scene.transferFunction = tf;
        scene.parameters["early_termination"] = 1.0;
        engine().setVolume(v);
        const Image unlit = engine().render(scene);
        scene.parameters["shading"] = 1.0;
        scene.parameters["ka"] = ka, scene.parameters["kd"] = kd, scene.parameters["ks"] = ks;
        const Image lit = engine().render(scene);
        const double opacity = 1.0 - std::pow(1.0 - a, 6);
        const glm::dvec3 colour = axis == 0 ? ka * c : (ka + kd) * c + glm::dvec3(ks);
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(unlit.at(2, 3)[ch], c[ch] * opacity, 1e-3) << "shading is off by default";
            EXPECT_NEAR(lit.at(2, 3)[ch], colour[ch] * opacity, 1e-3) << "ramp along axis " << axis;
        }
    }
}

}  // namespace
}  // namespace voxlab::testing
