// Tests for the image metrics against their definitions, computed here by
// other means: closed forms for flat images, a brute-force window, and
// properties any correct SSIM has.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "voxlab/error.h"
#include "voxlab/image_metrics.h"

namespace voxlab {
namespace {

Image flat(int w, int h, float v) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.set(x, y, glm::vec4(v, v, v, 1.0f));
    return img;
}

Image noise(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image img(w, h);
    for (auto& p : img.rgba) p = u(rng);
    return img;
}

// Largest cluster: groups drawn by hand, counted by hand.
TEST(ImageMetrics, LargestClusterCountsEightConnectedGroups) {
    Image a(16, 16), b(16, 16);
    auto off = [&](int x, int y, float by) { b.rgba[(std::size_t(y) * 16 + x) * 4 + 1] = by; };
    // An L of 5 (4-connected), a diagonal chain of 3 (8-connected only), two singles.
    for (auto [x, y] : {std::pair{2, 2}, {2, 3}, {2, 4}, {3, 4}, {4, 4}}) off(x, y, 0.5f);
    for (auto [x, y] : {std::pair{10, 2}, {11, 3}, {12, 4}}) off(x, y, 0.5f);
    off(8, 12, 0.5f);
    off(14, 14, 0.5f);
    EXPECT_EQ(largestCluster(a, b, 0.1), 5);
    EXPECT_EQ(largestCluster(a, b, 0.6), 0);  // nothing is off by that much
    off(3, 3, 0.5f);                          // joins nothing new: the L becomes 6
    EXPECT_EQ(largestCluster(a, b, 0.1), 6);
    off(9, 1, 0.05f);                         // below the threshold: does not count
    EXPECT_EQ(largestCluster(a, b, 0.1), 6);
    EXPECT_EQ(largestCluster(a, b, 0.01), 6); // counted now, but it touches only the chain (3 + 1)
    // A whole image off: one group, without overflowing anything.
    Image c(300, 300), d(300, 300);
    std::fill(d.rgba.begin(), d.rgba.end(), 1.0f);
    EXPECT_EQ(largestCluster(c, d, 0.5), 300 * 300);
}

TEST(ImageMetrics, PixelDifferenceAndPsnrOfKnownImages) {
    const Image a = flat(20, 10, 0.25f), b = flat(20, 10, 0.5f);
    Image c = a;
    c.set(3, 4, glm::vec4(0.25f, 0.9f, 0.25f, 1.0f));  // one pixel, one channel off by 0.65
    const PixelDifference d = pixelDifference(a, c, 0.1);
    EXPECT_NEAR(d.max, 0.65, 1e-6);
    EXPECT_NEAR(d.mean, 0.65 / 200.0, 1e-7);
    EXPECT_DOUBLE_EQ(d.fractionAbove, 1.0 / 200.0);
    // PSNR of a uniform error e: 10 log10(1 / e^2).
    EXPECT_NEAR(psnr(a, b), 10.0 * std::log10(1.0 / (0.25 * 0.25)), 1e-9);
    EXPECT_TRUE(std::isinf(psnr(a, a)));
    // Values are compared as displayed: clamped to [0, 1].
    EXPECT_DOUBLE_EQ(pixelDifference(flat(4, 4, 1.0f), flat(4, 4, 3.0f), 0.0).max, 0.0);
    EXPECT_THROW(pixelDifference(a, flat(10, 20, 0.0f), 0.1), Error);
}

// Flat images: variances and covariance vanish, so
// SSIM = (2ab + C1) / (a^2 + b^2 + C1) everywhere.
TEST(ImageMetrics, SsimOfFlatImagesHasItsClosedForm) {
    const double c1 = 1e-4;
    for (auto [a, b] : {std::pair{0.2, 0.6}, std::pair{0.0, 1.0}, std::pair{0.5, 0.5}}) {
        const SsimResult r = ssim(flat(30, 20, float(a)), flat(30, 20, float(b)));
        EXPECT_NEAR(r.mean, (2 * a * b + c1) / (a * a + b * b + c1), 1e-6) << a << " " << b;
        EXPECT_EQ(r.mapWidth, 20);
        EXPECT_EQ(r.mapHeight, 10);
    }
}

// One 11 x 11 window, computed here from the formula with its own Gaussian.
TEST(ImageMetrics, SsimOfOneWindowMatchesTheFormula) {
    const Image a = noise(11, 11, 1), b = noise(11, 11, 2);
    double want = 0.0;
    for (int c = 0; c < 3; ++c) {
        double wsum = 0, ma = 0, mb = 0;
        std::vector<double> w(121);
        for (int k = 0; k < 121; ++k) {
            const double dx = k % 11 - 5, dy = k / 11 - 5;
            w[k] = std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
            wsum += w[k];
        }
        for (int k = 0; k < 121; ++k) {
            w[k] /= wsum;
            ma += w[k] * a.at(k % 11, k / 11)[c];
            mb += w[k] * b.at(k % 11, k / 11)[c];
        }
        double va = 0, vb = 0, cov = 0;
        for (int k = 0; k < 121; ++k) {
            const double da = a.at(k % 11, k / 11)[c] - ma, db = b.at(k % 11, k / 11)[c] - mb;
            va += w[k] * da * da, vb += w[k] * db * db, cov += w[k] * da * db;
        }
        const double c1 = 1e-4, c2 = 9e-4;
        want += (2 * ma * mb + c1) * (2 * cov + c2) / ((ma * ma + mb * mb + c1) * (va + vb + c2)) / 3.0;
    }
    const SsimResult r = ssim(a, b);
    ASSERT_EQ(r.map.size(), 1u);
    EXPECT_NEAR(r.mean, want, 1e-6);
}

// Every position of the map, against the formula with a window of w x h
// placed there (2-D Gaussian weights, variances about the means): the map is
// row by row, position (x0, y0) the window's corner. Images larger than the
// window in both axes, and one smaller than it in x (the window clips).
TEST(ImageMetrics, SsimMapMatchesTheFormulaAtEveryPosition) {
    const auto formula = [](const Image& a, const Image& b, int x0, int y0, int ww, int wh) {
        std::vector<double> w(std::size_t(ww) * wh);
        double wsum = 0.0, value = 0.0;
        for (int k = 0; k < ww * wh; ++k) {
            const double dx = k % ww - (ww - 1) / 2.0, dy = k / ww - (wh - 1) / 2.0;
            wsum += w[std::size_t(k)] = std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
        }
        for (int c = 0; c < 3; ++c) {
            double ma = 0, mb = 0, va = 0, vb = 0, cov = 0;
            for (int k = 0; k < ww * wh; ++k) {
                ma += w[std::size_t(k)] / wsum * a.at(x0 + k % ww, y0 + k / ww)[c];
                mb += w[std::size_t(k)] / wsum * b.at(x0 + k % ww, y0 + k / ww)[c];
            }
            for (int k = 0; k < ww * wh; ++k) {
                const double da = a.at(x0 + k % ww, y0 + k / ww)[c] - ma, db = b.at(x0 + k % ww, y0 + k / ww)[c] - mb;
                va += w[std::size_t(k)] / wsum * da * da, vb += w[std::size_t(k)] / wsum * db * db;
                cov += w[std::size_t(k)] / wsum * da * db;
            }
            value += (2 * ma * mb + 1e-4) * (2 * cov + 9e-4) / ((ma * ma + mb * mb + 1e-4) * (va + vb + 9e-4)) / 3.0;
        }
        return value;
    };
    for (const auto& [w, h] : {std::pair{23, 17}, std::pair{7, 14}}) {
        const Image a = noise(w, h, 11), b = noise(w, h, 12);
        Image c = a;  // a with smooth changes: SSIM well away from 0
        for (auto& v : c.rgba) v = std::clamp(v * 0.8f + 0.1f, 0.0f, 1.0f);
        for (const Image* other : std::initializer_list<const Image*>{&b, &c}) {
            const SsimResult r = ssim(a, *other);
            const int ww = std::min(11, w), wh = std::min(11, h);
            ASSERT_EQ(r.mapWidth, w - ww + 1);
            ASSERT_EQ(r.mapHeight, h - wh + 1);
            double sum = 0.0;
            for (int y0 = 0; y0 < r.mapHeight; ++y0)
                for (int x0 = 0; x0 < r.mapWidth; ++x0) {
                    const double want = formula(a, *other, x0, y0, ww, wh);
                    sum += want;
                    ASSERT_NEAR(r.map[std::size_t(y0) * r.mapWidth + x0], want, 1e-6) << w << "x" << h << " at " << x0 << "," << y0;
                }
            EXPECT_NEAR(r.mean, sum / double(r.map.size()), 1e-9);
        }
    }
}

TEST(ImageMetrics, SsimPropertiesOnNoise) {
    const Image a = noise(40, 30, 3), b = noise(40, 30, 4);
    EXPECT_NEAR(ssim(a, a).mean, 1.0, 1e-9);
    EXPECT_NEAR(ssim(a, a).min, 1.0, 1e-9);
    // Symmetric, and unrelated noise has almost no structure in common.
    EXPECT_NEAR(ssim(a, b).mean, ssim(b, a).mean, 1e-9);
    EXPECT_LT(ssim(a, b).mean, 0.1);
    // A local defect lowers the map's minimum far more than its mean.
    Image c = a;
    for (int y = 10; y < 14; ++y)
        for (int x = 10; x < 14; ++x) c.set(x, y, glm::vec4(0.5f));
    const SsimResult r = ssim(a, c);
    EXPECT_LT(r.min, 0.8);
    EXPECT_GT(r.mean, 0.85);
    // Images smaller than the window still get a score.
    EXPECT_NEAR(ssim(noise(5, 7, 5), noise(5, 7, 5)).mean, 1.0, 1e-9);
}

}  // namespace
}  // namespace voxlab
