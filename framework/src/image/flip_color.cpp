// voxlab: FLIP's colour pipeline (the paper's "Color Pipeline" section):
// sRGB -> linear RGB -> XYZ -> opponent space YyCxCz, spatial filtering
// with the contrast sensitivity functions, back to linear RGB, then
// Hunt-adjusted L*a*b*, the HyAB distance, and its compression and
// redistribution into [0, 1].
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "flip_internal.h"

namespace voxlab::flip_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Linear sRGB to CIE XYZ, derived from the sRGB primaries (x, y) = (0.64,
// 0.33), (0.30, 0.60), (0.15, 0.06) and the D65 white point (0.3127, 0.3290)
// of IEC 61966-2-1, scaled so that white has Y = 1; and its inverse.
constexpr float kRgbToXyz[3][3] = {{0.4123907993f, 0.3575843394f, 0.1804807884f},
                                   {0.2126390059f, 0.7151686788f, 0.0721923154f},
                                   {0.0193308187f, 0.1191947798f, 0.9505321522f}};
constexpr float kXyzToRgb[3][3] = {{3.2409699419f, -1.5373831776f, -0.4986107603f},
                                   {-0.9692436363f, 1.8759675015f, 0.0415550574f},
                                   {0.0556300797f, -0.2039769589f, 1.0569715142f}};

// The reference white: XYZ of linear RGB (1, 1, 1), i.e. D65 with Y = 1.
constexpr float kWhite[3] = {kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2],
                             kRgbToXyz[1][0] + kRgbToXyz[1][1] + kRgbToXyz[1][2],
                             kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2]};

// The paper's table of contrast sensitivity functions, one per opponent
// channel, each a sum of two Gaussians in frequency f (cycles per degree):
// S(f) = a1 exp(-b1 f^2) + a2 exp(-b2 f^2). Only blue-yellow uses the second.
struct CsfParameters {
    double a1, b1, a2, b2;
};
constexpr CsfParameters kCsfAchromatic = {1.0, 0.0047, 0.0, 1e-5};
constexpr CsfParameters kCsfRedGreen = {1.0, 0.0053, 0.0, 1e-5};
constexpr CsfParameters kCsfBlueYellow = {34.1, 0.04, 13.5, 0.025};

// The colour metric's constants: HyAB distances are raised to qc; the
// distances below pc times the largest one are spread linearly over
// [0, pt], the rest over [pt, 1].
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95;

float decodeSrgb(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Decoding, clamped to [0, 1]. Images read from PNGs hold only the values
// k / 255, whose decodings are looked up rather than computed.
float srgbToLinear(float c) {
    static const std::vector<float> table = [] {
        std::vector<float> t(256);
        for (int k = 0; k < 256; ++k) t[k] = decodeSrgb(k / 255.0f);
        return t;
    }();
    c = std::clamp(c, 0.0f, 1.0f);
    const float scaled = c * 255.0f;
    const int k = int(scaled);
    return float(k) == scaled ? table[k] : decodeSrgb(c);
}

// The cube root of t > 0 with a relative error below 3e-7 (float
// precision), six times faster than std::cbrt, which took a fifth of FLIP's
// time. A float's bits, read as an integer, are about 2^23 (log2 t + 127);
// a third of that plus 2^23 (2/3) 127 are those of a first guess within 6%
// of t^(1/3). Two steps of Halley's method, y <- y (y^3 + 2t) / (2 y^3 + t),
// each of which about cubes the relative error, finish it.
float cubeRoot(float t) {
    std::uint32_t bits;
    std::memcpy(&bits, &t, sizeof bits);
    bits = bits / 3 + 710235477u;
    float y;
    std::memcpy(&y, &bits, sizeof y);
    for (int step = 0; step < 2; ++step) {
        const float y3 = y * y * y;
        y = y * (y3 + 2.0f * t) / (2.0f * y3 + t);
    }
    return y;
}

// The CIE L*a*b* companding function (cube root with a linear toe).
float labCompand(float t) {
    constexpr float delta = 6.0f / 29.0f;
    return t > delta * delta * delta ? cubeRoot(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
}

// One of the Gaussians of a CSF as a 1D spatial kernel. The inverse Fourier
// transform of exp(-b f^2) is sqrt(pi / b) exp(-pi^2 x^2 / b), x in degrees;
// x = i / ppd at tap i. Its 2D version, a product of two of these, is
// normalised along with the other Gaussian in csfFilter.
std::vector<double> csfGaussian(double b, int radius, double pixelsPerDegree) {
    std::vector<double> g(2 * radius + 1);
    for (int i = -radius; i <= radius; ++i) {
        const double x = i / pixelsPerDegree;
        g[i + radius] = std::exp(-kPi * kPi * x * x / b);
    }
    return g;
}

Kernel normalised(const std::vector<double>& g, double& sum) {
    sum = 0.0;
    for (double v : g) sum += v;
    Kernel k;
    for (double v : g) k.taps.push_back(float(v / sum));
    return k;
}

// Filters one opponent channel with its CSF ("Spatial filtering"). The 2D
// kernel is a1 sqrt(pi/b1) G1(x) G1(y) + a2 sqrt(pi/b2) G2(x) G2(y) on a
// square of radius ceil(3 sigma_max ppd), with sigma_max the standard
// deviation of the widest Gaussian (b = 0.04: sigma = sqrt(b / (2 pi^2))
// degrees), divided by its sum. Each Gaussian term is separable, so the
// kernel is applied as a weighted sum of two separable filters with the
// weights each term has in the normalised 2D kernel.
Plane csfFilter(const Plane& channel, const CsfParameters& csf, double pixelsPerDegree) {
    const double sigmaMax = std::sqrt(std::max({kCsfAchromatic.b1, kCsfRedGreen.b1, kCsfBlueYellow.b1,
                                                kCsfBlueYellow.b2}) / (2.0 * kPi * kPi));
    const int radius = int(std::ceil(3.0 * sigmaMax * pixelsPerDegree));
    double sum1 = 0.0, sum2 = 0.0;
    const Kernel g1 = normalised(csfGaussian(csf.b1, radius, pixelsPerDegree), sum1);
    if (csf.a2 == 0.0) return filterSeparable(channel, g1, g1);
    const Kernel g2 = normalised(csfGaussian(csf.b2, radius, pixelsPerDegree), sum2);
    const double mass1 = csf.a1 * std::sqrt(kPi / csf.b1) * sum1 * sum1;
    const double mass2 = csf.a2 * std::sqrt(kPi / csf.b2) * sum2 * sum2;
    const float w1 = float(mass1 / (mass1 + mass2)), w2 = float(mass2 / (mass1 + mass2));
    Plane out = filterSeparable(channel, g1, g1);
    const Plane second = filterSeparable(channel, g2, g2);
    for (std::size_t i = 0; i < out.values.size(); ++i) out.values[i] = w1 * out.values[i] + w2 * second.values[i];
    return out;
}

// A pixel in Hunt-adjusted L*a*b*.
struct HuntLab {
    float l, a, b;
};

// A filtered YyCxCz pixel back to linear RGB, clamped to the RGB cube (the
// filters can leave it), then to L*a*b* with the same white, and the Hunt
// adjustment ("Color metric"): colourfulness grows with luminance, so a*
// and b* are scaled by 0.01 L*.
HuntLab opponentToHuntLab(float yy, float cx, float cz) {
    const float yRel = (yy + 16.0f) / 116.0f;
    const float xyz[3] = {(cx / 500.0f + yRel) * kWhite[0], yRel * kWhite[1], (yRel - cz / 200.0f) * kWhite[2]};
    float rgb[3];
    for (int r = 0; r < 3; ++r)
        rgb[r] = std::clamp(kXyzToRgb[r][0] * xyz[0] + kXyzToRgb[r][1] * xyz[1] + kXyzToRgb[r][2] * xyz[2], 0.0f, 1.0f);
    float f[3];
    for (int r = 0; r < 3; ++r)
        f[r] = labCompand((kRgbToXyz[r][0] * rgb[0] + kRgbToXyz[r][1] * rgb[1] + kRgbToXyz[r][2] * rgb[2]) / kWhite[r]);
    const float l = 116.0f * f[1] - 16.0f;
    return {l, 0.01f * l * 500.0f * (f[0] - f[1]), 0.01f * l * 200.0f * (f[1] - f[2])};
}

// HyAB (Abasi, Tehran, Fairchild 2020): city-block distance in lightness
// plus Euclidean distance in the chromatic plane.
float hyab(const HuntLab& p, const HuntLab& q) {
    return std::abs(p.l - q.l) + std::sqrt((p.a - q.a) * (p.a - q.a) + (p.b - q.b) * (p.b - q.b));
}

// The largest compressed distance, cmax: that between pure green and pure
// blue, the most distant colours of the RGB cube in this space.
double maxCompressedDistance() {
    const auto opponentOf = [](const float rgb[3]) {
        float xyz[3];
        for (int r = 0; r < 3; ++r)
            xyz[r] = (kRgbToXyz[r][0] * rgb[0] + kRgbToXyz[r][1] * rgb[1] + kRgbToXyz[r][2] * rgb[2]) / kWhite[r];
        return opponentToHuntLab(116.0f * xyz[1] - 16.0f, 500.0f * (xyz[0] - xyz[1]), 200.0f * (xyz[1] - xyz[2]));
    };
    const float green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    return std::pow(double(hyab(opponentOf(green), opponentOf(blue))), kQc);
}

// Compression and redistribution: e = HyAB^qc; the small errors below
// pc * cmax take the range [0, pt], the rest [pt, 1], so that visible
// differences stand out in the map.
float redistribute(float distance, float cmax) {
    const float e = std::pow(distance, float(kQc));
    const float knee = float(kPc) * cmax;
    const float out = e < knee ? float(kPt) * e / knee : float(kPt) + (e - knee) / (cmax - knee) * float(1.0 - kPt);
    return std::min(out, 1.0f);
}

}  // namespace

// Decoding (IEC 61966-2-1), the RGB to XYZ matrix, then the opponent space
// YyCxCz of Johnson and Fairchild: a linearised CIELAB,
// Yy = 116 Y/Yw - 16, Cx = 500 (X/Xw - Y/Yw), Cz = 200 (Y/Yw - Z/Zw).
OpponentImage toOpponent(const Image& srgb) {
    OpponentImage o{Plane(srgb.width, srgb.height), Plane(srgb.width, srgb.height), Plane(srgb.width, srgb.height)};
    for (std::size_t i = 0; i < o.yy.values.size(); ++i) {
        const float* p = &srgb.rgba[i * 4];
        const float rgb[3] = {srgbToLinear(p[0]), srgbToLinear(p[1]), srgbToLinear(p[2])};
        float rel[3];
        for (int r = 0; r < 3; ++r)
            rel[r] = (kRgbToXyz[r][0] * rgb[0] + kRgbToXyz[r][1] * rgb[1] + kRgbToXyz[r][2] * rgb[2]) / kWhite[r];
        o.yy.values[i] = 116.0f * rel[1] - 16.0f;
        o.cx.values[i] = 500.0f * (rel[0] - rel[1]);
        o.cz.values[i] = 200.0f * (rel[1] - rel[2]);
    }
    return o;
}

Plane colorError(const OpponentImage& reference, const OpponentImage& test, double pixelsPerDegree) {
    const auto filtered = [&](const OpponentImage& o) {
        return OpponentImage{csfFilter(o.yy, kCsfAchromatic, pixelsPerDegree),
                             csfFilter(o.cx, kCsfRedGreen, pixelsPerDegree),
                             csfFilter(o.cz, kCsfBlueYellow, pixelsPerDegree)};
    };
    const OpponentImage r = filtered(reference), t = filtered(test);
    const float cmax = float(maxCompressedDistance());
    Plane error(reference.yy.width, reference.yy.height);
    for (std::size_t i = 0; i < error.values.size(); ++i) {
        const HuntLab p = opponentToHuntLab(r.yy.values[i], r.cx.values[i], r.cz.values[i]);
        const HuntLab q = opponentToHuntLab(t.yy.values[i], t.cx.values[i], t.cz.values[i]);
        error.values[i] = redistribute(hyab(p, q), cmax);
    }
    return error;
}

}  // namespace voxlab::flip_detail
