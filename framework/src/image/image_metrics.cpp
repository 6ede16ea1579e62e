// voxlab: image metrics (see image_metrics.h for the definitions).
#include "voxlab/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "voxlab/error.h"

namespace voxlab {

namespace {

void checkSizes(const Image& a, const Image& b, const char* what) {
    if (a.width != b.width || a.height != b.height)
        throw Error(std::string(what) + ": images differ in size (" + std::to_string(a.width) + "x" +
                    std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                    std::to_string(b.height) + ")");
}

double channel(const Image& img, int x, int y, int c) {
    return std::clamp(double(img.at(x, y)[c]), 0.0, 1.0);
}

constexpr int kWindow = 11;
constexpr double kSigma = 1.5;

}  // namespace

PixelDifference pixelDifference(const Image& a, const Image& b, double threshold) {
    checkSizes(a, b, "pixel difference");
    PixelDifference d;
    std::size_t above = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            double worst = 0.0;
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(channel(a, x, y, c) - channel(b, x, y, c)));
            d.max = std::max(d.max, worst);
            d.mean += worst;
            above += worst > threshold;
        }
    const double n = double(a.width) * a.height;
    if (n > 0) d.mean /= n, d.fractionAbove = double(above) / n;
    return d;
}

int largestCluster(const Image& a, const Image& b, double threshold) {
    checkSizes(a, b, "cluster size");
    const int w = a.width, h = a.height;
    std::vector<char> bad(std::size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double worst = 0.0;
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(channel(a, x, y, c) - channel(b, x, y, c)));
            bad[std::size_t(y) * w + x] = worst > threshold;
        }
    // Flood fill from each bad pixel not yet counted (an explicit stack: a
    // whole image of bad pixels must not overflow the call stack).
    int largest = 0;
    std::vector<int> stack;
    for (int start = 0; start < w * h; ++start) {
        if (!bad[std::size_t(start)]) continue;
        bad[std::size_t(start)] = 0;
        stack.assign(1, start);
        int size = 0;
        while (!stack.empty()) {
            const int p = stack.back();
            stack.pop_back();
            ++size;
            const int px = p % w, py = p / w;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int qx = px + dx, qy = py + dy;
                    if (qx < 0 || qy < 0 || qx >= w || qy >= h || !bad[std::size_t(qy) * w + qx]) continue;
                    bad[std::size_t(qy) * w + qx] = 0;
                    stack.push_back(qy * w + qx);
                }
        }
        largest = std::max(largest, size);
    }
    return largest;
}

double psnr(const Image& a, const Image& b) {
    checkSizes(a, b, "PSNR");
    double sum = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const double e = channel(a, x, y, c) - channel(b, x, y, c);
                sum += e * e;
            }
    const double mse = sum / (3.0 * a.width * a.height);
    return mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(1.0 / mse);
}

namespace {

// The Gaussian taps of one axis of the SSIM window, n of them (11, or the
// image's size when it is smaller), summing to 1.
std::vector<double> ssimTaps(int n) {
    std::vector<double> g(std::size_t(n), 0.0);
    double total = 0.0;
    for (int i = 0; i < n; ++i) {
        const double t = i - (n - 1) / 2.0;
        total += g[std::size_t(i)] = std::exp(-t * t / (2.0 * kSigma * kSigma));
    }
    for (double& v : g) v /= total;
    return g;
}

// The window's weighted means of a, b, a², b² and a·b in channel c, at every
// position where the window fits: moments[k][y0 * mapWidth + x0]. The 2-D
// window is the product of its two axes' taps, so a pass along x and then one
// along y give the same sums as the 121 products per position (a sixth of the
// work; this was a third of a grading run's own CPU time).
std::array<std::vector<double>, 5> windowMoments(const Image& a, const Image& b, int c,
                                                  const std::vector<double>& gx, const std::vector<double>& gy) {
    const int wx = int(gx.size()), wy = int(gy.size()), mw = a.width - wx + 1, mh = a.height - wy + 1;
    std::array<std::vector<double>, 5> rows, out;  // rows: after the pass along x, a.height rows of mw
    for (auto& r : rows) r.assign(std::size_t(mw) * a.height, 0.0);
    std::vector<double> va(std::size_t(a.width)), vb(std::size_t(a.width));
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) va[std::size_t(x)] = channel(a, x, y, c), vb[std::size_t(x)] = channel(b, x, y, c);
        for (int x0 = 0; x0 < mw; ++x0) {
            double m[5] = {0, 0, 0, 0, 0};
            for (int i = 0; i < wx; ++i) {
                const double w = gx[std::size_t(i)], p = va[std::size_t(x0 + i)], q = vb[std::size_t(x0 + i)];
                m[0] += w * p, m[1] += w * q, m[2] += w * p * p, m[3] += w * q * q, m[4] += w * p * q;
            }
            for (int k = 0; k < 5; ++k) rows[std::size_t(k)][std::size_t(y) * mw + x0] = m[k];
        }
    }
    for (int k = 0; k < 5; ++k) {
        out[std::size_t(k)].assign(std::size_t(mw) * mh, 0.0);
        for (int y0 = 0; y0 < mh; ++y0)
            for (int j = 0; j < wy; ++j) {
                const double w = gy[std::size_t(j)];
                const double* from = &rows[std::size_t(k)][std::size_t(y0 + j) * mw];
                double* to = &out[std::size_t(k)][std::size_t(y0) * mw];
                for (int x0 = 0; x0 < mw; ++x0) to[x0] += w * from[x0];
            }
    }
    return out;
}

}  // namespace

SsimResult ssim(const Image& a, const Image& b) {
    checkSizes(a, b, "SSIM");
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    // The window: 11 taps of a Gaussian per axis, clipped to the image when
    // it is smaller, placed at every position where it fits.
    const std::vector<double> gx = ssimTaps(std::min(kWindow, a.width)), gy = ssimTaps(std::min(kWindow, a.height));
    SsimResult r;
    r.mapWidth = a.width - int(gx.size()) + 1;
    r.mapHeight = a.height - int(gy.size()) + 1;
    std::vector<double> value(std::size_t(r.mapWidth) * r.mapHeight, 0.0);
    for (int c = 0; c < 3; ++c) {
        const std::array<std::vector<double>, 5> m = windowMoments(a, b, c, gx, gy);
        for (std::size_t p = 0; p < value.size(); ++p) {
            const double ma = m[0][p], mb = m[1][p];
            const double varA = m[2][p] - ma * ma, varB = m[3][p] - mb * mb, cov = m[4][p] - ma * mb;
            value[p] += (2 * ma * mb + c1) * (2 * cov + c2) / ((ma * ma + mb * mb + c1) * (varA + varB + c2));
        }
    }
    r.map.assign(value.size(), 0.0f);
    double sum = 0.0, lowest = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < value.size(); ++p) {
        const double v = value[p] / 3.0;
        r.map[p] = float(v);
        sum += v;
        lowest = std::min(lowest, v);
    }
    r.mean = r.map.empty() ? 1.0 : sum / double(r.map.size());
    r.min = r.map.empty() ? 1.0 : lowest;
    return r;
}

}  // namespace voxlab
