// voxlab: label maps on the CPU (see label_map.h).
//
// The distance field is the one piece with an algorithm worth a note. The
// squared Euclidean distance to a set of voxels is separable: first, along
// each x row, the squared distance to the nearest set voxel in that row;
// then, along each y column, the lower envelope of parabolas
// s_y^2 (q - p)^2 + f(p) over the previous pass's values f; then the same
// along z. Each pass is linear in its line's length (Felzenszwalb &
// Huttenlocher, "Distance transforms of sampled functions", Theory of
// Computing 8, 2012), so a 256^3 field costs three sweeps, not a search.
#include "voxlab/label_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "voxlab/error.h"

namespace voxlab {
namespace {

std::string dimsText(glm::ivec3 d) {
    return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

// The squared distance transform of one line of `n` values f (taken
// `stride` apart in `data`), weighted by w = spacing^2:
// d(q) = min_p w (q - p)^2 + f(p). Infinite values are points not in the set.
void transformLine(float* data, int n, std::size_t stride, double w, std::vector<double>& f,
                   std::vector<int>& v, std::vector<double>& z) {
    const double inf = std::numeric_limits<double>::infinity();
    for (int q = 0; q < n; ++q) f[q] = data[std::size_t(q) * stride];
    int k = -1;  // rightmost parabola of the lower envelope
    for (int q = 0; q < n; ++q) {
        if (f[q] == inf) continue;
        // Where parabola q starts to lie below parabola v[k].
        double s = -inf;
        while (k >= 0) {
            const int p = v[k];
            s = ((f[q] + w * q * q) - (f[p] + w * p * p)) / (2.0 * w * (q - p));
            if (s > z[k]) break;
            --k;
        }
        ++k;
        v[k] = q;
        z[k] = k == 0 ? -inf : s;
        z[k + 1] = inf;
    }
    if (k < 0) return;  // no point of the set on this line: all stay infinite
    int j = 0;
    for (int q = 0; q < n; ++q) {
        while (z[j + 1] < q) ++j;
        const double d = q - v[j];
        data[std::size_t(q) * stride] = float(w * d * d + f[v[j]]);
    }
}

}  // namespace

std::vector<std::uint16_t> checkedLabels(const Volume& labels, const Volume& volume) {
    if (labels.dims() != volume.dims())
        throw Error(labels.name() + ": the label map is " + dimsText(labels.dims()) + " but the volume is " +
                    dimsText(volume.dims()));
    std::vector<std::uint16_t> out(labels.voxelCount());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const double v = labels.valueAt(i);
        if (!(v >= 0.0 && v <= kMaxLabel && v == std::floor(v))) {
            const glm::ivec3 d = labels.dims();
            const std::size_t x = i % std::size_t(d.x), y = i / std::size_t(d.x) % std::size_t(d.y),
                              z = i / (std::size_t(d.x) * std::size_t(d.y));
            char value[32];
            std::snprintf(value, sizeof value, "%g", v);
            throw Error(labels.name() + ": a label map holds whole numbers 0.." + std::to_string(kMaxLabel) +
                        ", not " + value + " (voxel " + std::to_string(x) + " " + std::to_string(y) + " " +
                        std::to_string(z) + ")");
        }
        out[i] = std::uint16_t(v);
    }
    return out;
}

std::vector<std::uint64_t> labelCounts(const std::vector<std::uint16_t>& labels) {
    std::vector<std::uint64_t> counts;
    for (std::uint16_t l : labels) {
        if (l >= counts.size()) counts.resize(std::size_t(l) + 1, 0);
        ++counts[l];
    }
    return counts;
}

std::vector<float> distanceToLabel(const std::vector<std::uint16_t>& labels, glm::ivec3 dims, glm::dvec3 spacing,
                                   int target) {
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<float> d(labels.size());
    bool any = false;
    for (std::size_t i = 0; i < labels.size(); ++i) {
        d[i] = labels[i] == target ? 0.0f : inf;
        any = any || labels[i] == target;
    }
    if (!any) throw Error("labels.distance.to: no voxel carries label " + std::to_string(target));
    const int longest = std::max(dims.x, std::max(dims.y, dims.z));
    std::vector<double> f(std::size_t(longest) + 1), z(std::size_t(longest) + 1);
    std::vector<int> v(std::size_t(longest) + 1);
    const std::size_t sx = 1, sy = std::size_t(dims.x), sz = std::size_t(dims.x) * std::size_t(dims.y);
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            transformLine(&d[k * sz + j * sy], dims.x, sx, spacing.x * spacing.x, f, v, z);
    for (int k = 0; k < dims.z; ++k)
        for (int i = 0; i < dims.x; ++i)
            transformLine(&d[k * sz + i * sx], dims.y, sy, spacing.y * spacing.y, f, v, z);
    for (int j = 0; j < dims.y; ++j)
        for (int i = 0; i < dims.x; ++i)
            transformLine(&d[j * sy + i * sx], dims.z, sz, spacing.z * spacing.z, f, v, z);
    for (float& x : d) x = std::sqrt(x);
    return d;
}

LabelRows labelRows(const LabelMap& map, const TransferFunction& sceneFunction, int largestLabel) {
    LabelRows out;
    out.tables.push_back(&sceneFunction);
    out.rows.assign(std::size_t(std::max(largestLabel, 0)) + 1, glm::vec2(0.0f));
    for (const LabelClass& c : map.classes) {
        if (c.label > largestLabel) continue;  // not in the data
        float row = 0.0f;
        if (!c.visible) {
            row = -1.0f;
        } else if (c.transferFunction) {
            row = float(out.tables.size());
            out.tables.push_back(&*c.transferFunction);
        }
        out.rows[std::size_t(c.label)].x = row;
    }
    if (map.distance) {
        const LabelDistance& d = *map.distance;
        for (int l = 0; l <= largestLabel; ++l) {
            const bool applies = d.applyTo.empty() ? l != d.to
                                                   : std::find(d.applyTo.begin(), d.applyTo.end(), l) != d.applyTo.end();
            out.rows[std::size_t(l)].y = applies ? 1.0f : 0.0f;
        }
    }
    return out;
}

}  // namespace voxlab
