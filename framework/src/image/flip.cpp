// voxlab: the FLIP metric (see voxlab/flip.h): the separable filtering both
// pipelines use, and the final combination of the colour and feature errors.
#include "voxlab/flip.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "flip_internal.h"
#include "voxlab/error.h"

namespace voxlab {

namespace flip_detail {

namespace {

constexpr std::size_t kPoolBytes = std::size_t(64) << 20;

// The pool behind Plane: spare buffers of this thread, and their bytes.
struct PlanePool {
    std::vector<std::vector<float>> spare;
    std::size_t bytes = 0;
};
thread_local PlanePool planePool;

}  // namespace

Plane::Plane(int w, int h) : width(w), height(h) {
    const std::size_t n = std::size_t(w) * h;
    std::vector<std::vector<float>>& spare = planePool.spare;
    for (std::size_t i = 0; i < spare.size(); ++i)
        if (spare[i].capacity() >= n) {
            values.swap(spare[i]);
            spare[i].swap(spare.back());
            spare.pop_back();
            planePool.bytes -= values.capacity() * sizeof(float);
            break;
        }
    values.resize(n);
}

Plane::~Plane() {
    const std::size_t bytes = values.capacity() * sizeof(float);
    if (bytes == 0 || planePool.bytes + bytes > kPoolBytes) return;
    planePool.bytes += bytes;
    planePool.spare.push_back(std::move(values));
}

namespace {

// The inner loops of both passes: dst[x] = sum_i taps[i] rows[i][x] for
// x in [0, n), where rows[i] points at the data tap i weighs. Pixels are
// taken in blocks of kBlock whose sums stay in registers while the taps
// are run through (the compiler turns the block loop into vector code).
//
// For a kernel whose taps sum to zero (the derivative detectors), the sum
// is taken of taps[i] (rows[i][x] - centre[x]) instead: the same in exact
// arithmetic, but exactly zero on flat regions, where rounding would
// otherwise leave noise of about 1e-8 that FLIP's square root of the
// feature difference turns into errors of 1e-4.
constexpr int kBlock = 16;

void weightedSum(const Kernel& k, const float* const* rows, int n, float* dst) {
    const int tapCount = int(k.taps.size());
    const float* taps = k.taps.data();
    static const std::vector<float> zeros(kBlock, 0.0f);
    const float* centre = k.zeroSum ? rows[k.radius()] : nullptr;
    int x = 0;
    for (; x + kBlock <= n; x += kBlock) {
        const float* c = centre ? centre + x : zeros.data();
        float sum[kBlock] = {};
        for (int i = 0; i < tapCount; ++i) {
            const float tap = taps[i];
            const float* src = rows[i] + x;
            for (int b = 0; b < kBlock; ++b) sum[b] += tap * (src[b] - c[b]);
        }
        for (int b = 0; b < kBlock; ++b) dst[x + b] = sum[b];
    }
    for (; x < n; ++x) {
        const float c = centre ? centre[x] : 0.0f;
        float sum = 0.0f;
        for (int i = 0; i < tapCount; ++i) sum += taps[i] * (rows[i][x] - c);
        dst[x] = sum;
    }
}

}  // namespace

// out(x, y) = sum_i k[i] in(x + i, y) along each row. The row is first
// copied with `radius` border pixels repeated on both sides, so that the
// sums run over contiguous memory without bounds checks.
Plane filterRows(const Plane& in, const Kernel& k) {
    Plane out(in.width, in.height);
    const int r = k.radius(), w = in.width, tapCount = 2 * r + 1;
    std::vector<float> padded(std::size_t(w) + 2 * r);
    std::vector<const float*> rows(tapCount);
    for (int i = 0; i < tapCount; ++i) rows[i] = padded.data() + i;
    for (int y = 0; y < in.height; ++y) {
        const float* row = &in.values[std::size_t(y) * w];
        std::fill(padded.begin(), padded.begin() + r, row[0]);
        std::copy(row, row + w, padded.begin() + r);
        std::fill(padded.begin() + r + w, padded.end(), row[w - 1]);
        weightedSum(k, rows.data(), w, &out.values[std::size_t(y) * w]);
    }
    return out;
}

// out(x, y) = sum_j k[j] in(x, y + j), rows outside the image replaced by
// the first or last row; whole rows at a time.
Plane filterColumns(const Plane& in, const Kernel& k) {
    Plane out(in.width, in.height);
    const int r = k.radius(), w = in.width, tapCount = 2 * r + 1;
    std::vector<const float*> rows(tapCount);
    for (int y = 0; y < in.height; ++y) {
        for (int j = -r; j <= r; ++j)
            rows[j + r] = &in.values[std::size_t(std::clamp(y + j, 0, in.height - 1)) * w];
        weightedSum(k, rows.data(), w, &out.values[std::size_t(y) * w]);
    }
    return out;
}

Plane filterSeparable(const Plane& in, const Kernel& horizontal, const Kernel& vertical) {
    return filterColumns(filterRows(in, horizontal), vertical);
}

}  // namespace flip_detail

FlipResult flip(const Image& reference, const Image& test, double pixelsPerDegree) {
    if (reference.width != test.width || reference.height != test.height)
        throw Error("FLIP: images differ in size (" + std::to_string(reference.width) + "x" +
                    std::to_string(reference.height) + " and " + std::to_string(test.width) + "x" +
                    std::to_string(test.height) + ")");
    if (reference.width <= 0 || reference.height <= 0) throw Error("FLIP: the images are empty");
    if (!(pixelsPerDegree > 0.0) || !std::isfinite(pixelsPerDegree))
        throw Error("FLIP: pixels per degree must be a positive number, not " + std::to_string(pixelsPerDegree));

    const flip_detail::OpponentImage r = flip_detail::toOpponent(reference);
    const flip_detail::OpponentImage t = flip_detail::toOpponent(test);

    FlipResult result;
    result.width = reference.width;
    result.height = reference.height;
    result.colorError = flip_detail::colorError(r, t, pixelsPerDegree).values;
    result.featureError = flip_detail::featureError(r, t, pixelsPerDegree).values;

    // The final difference ("Final Difference Map"): ΔE = ΔEc^(1 - ΔEf).
    // Feature differences lower the exponent and so raise the colour error;
    // with no feature difference the colour error is unchanged.
    result.map.resize(result.colorError.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < result.map.size(); ++i) {
        const float e = std::pow(result.colorError[i], 1.0f - result.featureError[i]);
        result.map[i] = e;
        sum += e;
        result.max = std::max(result.max, double(e));
    }
    result.mean = sum / double(result.map.size());
    return result;
}

double FlipResult::percentile(double p) const {
    if (!(p >= 0.0 && p <= 100.0)) throw Error("FLIP percentile: " + std::to_string(p) + " is not in [0, 100]");
    if (map.empty()) throw Error("FLIP percentile: the error map is empty");
    // Rank p/100 (n - 1) in the sorted values, interpolated between its neighbours.
    std::vector<float> sorted = map;
    const double rank = p / 100.0 * double(sorted.size() - 1);
    const std::size_t below = std::size_t(std::floor(rank));
    std::nth_element(sorted.begin(), sorted.begin() + below, sorted.end());
    const double low = sorted[below];
    if (below + 1 >= sorted.size()) return low;
    const double high = *std::min_element(sorted.begin() + below + 1, sorted.end());
    return low + (rank - double(below)) * (high - low);
}

}  // namespace voxlab
