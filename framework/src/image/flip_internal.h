// voxlab: the pieces of the FLIP metric (see voxlab/flip.h), shared by
// flip.cpp (filtering, the final combination), flip_color.cpp (the colour
// pipeline) and flip_features.cpp (the feature pipeline). Not installed.
#pragma once

#include <vector>

#include "voxlab/image.h"

namespace voxlab::flip_detail {

// One channel of an image: width*height floats, row 0 at the top, values
// unspecified until written.
//
// FLIP needs a few dozen such planes per call; fresh memory for each costs
// the system's page-zeroing about as much time as the metric itself. So a
// plane takes its memory from, and on destruction returns it to, a small
// pool kept per thread (at most kPoolBytes; buffers beyond are freed).
struct Plane {
    int width = 0, height = 0;
    std::vector<float> values;

    Plane() = default;
    Plane(int w, int h);
    ~Plane();
    Plane(Plane&&) = default;
    Plane& operator=(Plane&&) = default;
    Plane(const Plane&) = delete;
    Plane& operator=(const Plane&) = delete;
};

// A 1D filter of odd length 2 * radius + 1; taps[radius] is the centre.
// zeroSum marks kernels whose taps sum to zero (see filterSeparable).
struct Kernel {
    std::vector<float> taps;
    bool zeroSum = false;
    int radius() const { return int(taps.size()) / 2; }
};

// Filters the rows with horizontal, then the columns with vertical:
// out(x, y) = sum_ij horizontal[i] vertical[j] in(x + i, y + j), offsets
// from the centres, pixels outside the image replaced by the nearest border
// pixel. (A correlation; every kernel FLIP uses is symmetric or
// antisymmetric, and only magnitudes of antisymmetric responses are used.)
// Zero-sum kernels give exactly 0 where their input is constant.
Plane filterSeparable(const Plane& in, const Kernel& horizontal, const Kernel& vertical);

// Its two halves: filtering the rows, or the columns, only.
Plane filterRows(const Plane& in, const Kernel& k);
Plane filterColumns(const Plane& in, const Kernel& k);

// An image in the opponent space YyCxCz (flip_color.cpp): the input the
// colour and feature pipelines share.
struct OpponentImage {
    Plane yy, cx, cz;
};

// sRGB-encoded colours (clamped to [0, 1]) to YyCxCz.
OpponentImage toOpponent(const Image& srgb);

// The colour error ΔEc in [0, 1] per pixel (flip_color.cpp).
Plane colorError(const OpponentImage& reference, const OpponentImage& test, double pixelsPerDegree);

// The feature error ΔEf in [0, 1] per pixel (flip_features.cpp).
Plane featureError(const OpponentImage& reference, const OpponentImage& test, double pixelsPerDegree);

}  // namespace voxlab::flip_detail
