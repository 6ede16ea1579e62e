// voxlab: comparing two images (the grader's and the golden tests' metrics).
//
// All metrics read the images' RGB as displayed: each channel clamped to
// [0, 1] (what a PNG would store, before rounding). Images must have the
// same size.
//
//  - Pixel difference: per pixel, the largest |a - b| over r, g, b; the
//    report gives its maximum, its mean and the fraction of pixels above a
//    threshold.
//  - Largest cluster: the size, in pixels, of the largest 8-connected group
//    of pixels whose difference exceeds a threshold. Rasterisation noise
//    (another filtering path, another thread count) scatters single pixels
//    or short edge runs; a mistake that shows only on a thin feature or a
//    small structure makes a compact group, which this counts.
//  - PSNR: 10 log10(1 / MSE) over all channels, in dB (infinite for equal
//    images). For display only: it says little about where errors are.
//  - SSIM (Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image
//    quality assessment: from error visibility to structural similarity",
//    IEEE TIP 2004): for each 11 x 11 window, weighted by a Gaussian of
//    sigma 1.5 (normalised to sum 1),
//       SSIM = (2 mu_a mu_b + C1)(2 cov_ab + C2) / ((mu_a^2 + mu_b^2 + C1)(var_a + var_b + C2)),
//    with C1 = (0.01 L)^2, C2 = (0.03 L)^2 and L = 1. Windows are placed
//    only where they fit inside the image ("valid"), on each of r, g, b;
//    the map holds the mean over the channels, and the score is the map's
//    mean. The map's minimum shows the worst local structure. Images smaller
//    than 11 x 11 use one window clipped to the image, renormalised.
#pragma once

#include <vector>

#include "voxlab/image.h"

namespace voxlab {

struct PixelDifference {
    double max = 0.0;
    double mean = 0.0;
    double fractionAbove = 0.0;  // of pixels whose difference exceeds the threshold
};

PixelDifference pixelDifference(const Image& a, const Image& b, double threshold);

// The largest 8-connected group of pixels whose difference (largest |a - b|
// over r, g, b) exceeds `threshold`; 0 when there is none.
int largestCluster(const Image& a, const Image& b, double threshold);

double psnr(const Image& a, const Image& b);

struct SsimResult {
    double mean = 1.0;
    double min = 1.0;
    int mapWidth = 0, mapHeight = 0;
    std::vector<float> map;  // row by row; the window centred at (x + 5, y + 5)
};

SsimResult ssim(const Image& a, const Image& b);

}  // namespace voxlab
