// voxlab: image metrics (see image_metrics.h for the definitions).
#include "voxlab/image_metrics.h"

#include <algorithm>
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

SsimResult ssim(const Image& a, const Image& b) {
    checkSizes(a, b, "SSIM");
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    // The window: 11 taps of a Gaussian per axis, clipped to the image when
    // it is smaller, placed at every position where it fits.
    const int wx = std::min(kWindow, a.width), wy = std::min(kWindow, a.height);
    auto taps = [](int n) {
        std::vector<double> g(n);
        for (int i = 0; i < n; ++i) {
            const double t = i - (n - 1) / 2.0;
            g[i] = std::exp(-t * t / (2.0 * kSigma * kSigma));
        }
        return g;
    };
    const std::vector<double> gx = taps(wx), gy = taps(wy);
    double total = 0.0;
    for (double u : gx)
        for (double v : gy) total += u * v;

    SsimResult r;
    r.mapWidth = a.width - wx + 1;
    r.mapHeight = a.height - wy + 1;
    r.map.assign(std::size_t(r.mapWidth) * r.mapHeight, 0.0f);
    double sum = 0.0, lowest = std::numeric_limits<double>::infinity();
    for (int y0 = 0; y0 < r.mapHeight; ++y0)
        for (int x0 = 0; x0 < r.mapWidth; ++x0) {
            double value = 0.0;
            for (int c = 0; c < 3; ++c) {
                double ma = 0, mb = 0, aa = 0, bb = 0, ab = 0;
                for (int j = 0; j < wy; ++j)
                    for (int i = 0; i < wx; ++i) {
                        const double w = gx[i] * gy[j] / total;
                        const double va = channel(a, x0 + i, y0 + j, c), vb = channel(b, x0 + i, y0 + j, c);
                        ma += w * va, mb += w * vb;
                        aa += w * va * va, bb += w * vb * vb, ab += w * va * vb;
                    }
                const double varA = aa - ma * ma, varB = bb - mb * mb, cov = ab - ma * mb;
                value += (2 * ma * mb + c1) * (2 * cov + c2) / ((ma * ma + mb * mb + c1) * (varA + varB + c2));
            }
            value /= 3.0;
            r.map[std::size_t(y0) * r.mapWidth + x0] = float(value);
            sum += value;
            lowest = std::min(lowest, value);
        }
    r.mean = r.map.empty() ? 1.0 : sum / double(r.map.size());
    r.min = r.map.empty() ? 1.0 : lowest;
    return r;
}

}  // namespace voxlab
