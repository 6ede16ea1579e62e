// voxlab: FLIP's feature pipeline (the paper's "Feature Pipeline"
// section): differences in edges and points of the luminance, found with
// the first and second derivatives of a Gaussian about as wide as the eye's
// edge detectors.
#include <algorithm>
#include <cmath>

#include "flip_internal.h"

namespace voxlab::flip_detail {

namespace {

// The width w of the human edge detector in degrees, and the exponent qf
// that compresses feature differences.
constexpr double kEdgeWidth = 0.082, kQf = 0.5;

// The three 1D kernels the 2D detectors are built from. With
// g(x) = exp(-x^2 / (2 sigma^2)), sigma = 0.5 w ppd pixels, radius
// ceil(3 sigma):
//  - smooth: g, normalised to sum 1;
//  - firstDerivative: -x g(x), its positive taps scaled to sum 1 and its
//    negative ones to sum -1;
//  - secondDerivative: (x^2 / sigma^2 - 1) g(x), lobes scaled the same way.
// The paper normalises the 2D kernels, e.g. dG/dx(x, y) = -x g(x) g(y), so
// that their positive and negative parts sum to 1 and -1. The 2D kernel's
// positive part is (positive taps of the x kernel) times g(y), so its sum is
// a product of 1D sums: normalising the 1D pieces as above gives exactly the
// paper's 2D kernels, applied separably.
struct FeatureKernels {
    Kernel smooth, firstDerivative, secondDerivative;
};

Kernel withUnitLobes(const std::vector<double>& k) {
    double positive = 0.0, negative = 0.0;
    for (double v : k) (v > 0 ? positive : negative) += v;
    Kernel out;
    for (double v : k) out.taps.push_back(float(v > 0 ? v / positive : v / -negative));
    out.zeroSum = true;
    return out;
}

FeatureKernels featureKernels(double pixelsPerDegree) {
    const double sigma = 0.5 * kEdgeWidth * pixelsPerDegree;
    const int radius = int(std::ceil(3.0 * sigma));
    std::vector<double> g, first, second;
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        const double x = i, gauss = std::exp(-x * x / (2.0 * sigma * sigma));
        g.push_back(gauss);
        first.push_back(-x * gauss);
        second.push_back((x * x / (sigma * sigma) - 1.0) * gauss);
        sum += gauss;
    }
    FeatureKernels k;
    for (double v : g) k.smooth.taps.push_back(float(v / sum));
    k.firstDerivative = withUnitLobes(first);
    k.secondDerivative = withUnitLobes(second);
    return k;
}

// The luminance the detectors see: Y / Yw in [0, 1], recovered from the
// opponent space as (Yy + 16) / 116.
Plane normalisedLuminance(const OpponentImage& o) {
    Plane y(o.yy.width, o.yy.height);
    for (std::size_t i = 0; i < y.values.size(); ++i) y.values[i] = (o.yy.values[i] + 16.0f) / 116.0f;
    return y;
}

// Edge and point strength per pixel: the lengths of the 2D responses
// (x and y derivative) of the first- and second-derivative detectors.
struct FeatureStrength {
    Plane edge, point;
};

FeatureStrength featureStrength(const Plane& luminance, const FeatureKernels& k) {
    const Plane edgeX = filterSeparable(luminance, k.firstDerivative, k.smooth);
    const Plane pointX = filterSeparable(luminance, k.secondDerivative, k.smooth);
    const Plane smoothRows = filterRows(luminance, k.smooth);  // shared by both y-derivatives
    const Plane edgeY = filterColumns(smoothRows, k.firstDerivative);
    const Plane pointY = filterColumns(smoothRows, k.secondDerivative);
    FeatureStrength s{Plane(luminance.width, luminance.height), Plane(luminance.width, luminance.height)};
    for (std::size_t i = 0; i < s.edge.values.size(); ++i) {
        s.edge.values[i] = std::sqrt(edgeX.values[i] * edgeX.values[i] + edgeY.values[i] * edgeY.values[i]);
        s.point.values[i] = std::sqrt(pointX.values[i] * pointX.values[i] + pointY.values[i] * pointY.values[i]);
    }
    return s;
}

}  // namespace

// ΔEf = (max(|edge_r - edge_t|, |point_r - point_t|) / sqrt(2))^qf. Each
// directional response lies in [-1, 1] (unit lobes, luminance in [0, 1]), so
// the strengths lie in [0, sqrt(2)] and ΔEf in [0, 1].
Plane featureError(const OpponentImage& reference, const OpponentImage& test, double pixelsPerDegree) {
    const FeatureKernels k = featureKernels(pixelsPerDegree);
    const FeatureStrength r = featureStrength(normalisedLuminance(reference), k);
    const FeatureStrength t = featureStrength(normalisedLuminance(test), k);
    Plane error(reference.yy.width, reference.yy.height);
    for (std::size_t i = 0; i < error.values.size(); ++i) {
        const float edge = std::abs(r.edge.values[i] - t.edge.values[i]);
        const float point = std::abs(r.point.values[i] - t.point.values[i]);
        const float difference = std::max(edge, point) / std::sqrt(2.0f);
        error.values[i] = std::min(std::pow(difference, float(kQf)), 1.0f);
    }
    return error;
}

}  // namespace voxlab::flip_detail
