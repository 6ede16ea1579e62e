// voxlab: CPU gradient estimators (see gradients.h for the definitions).
#include "voxlab/gradients.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "voxlab/error.h"

namespace voxlab {

const char* gradientEstimatorName(GradientEstimator e) {
    return e == GradientEstimator::Central ? "central" : "sobel";
}

namespace {

// Converts the whole volume to float once (exact for every voxel type): the
// estimators read every voxel
// up to 26 times.
std::vector<float> valuesOf(const Volume& v) {
    std::vector<float> out(v.voxelCount());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = float(v.valueAt(i));
    return out;
}

// The difference along `axis` at (i,j,k) with the boundary rule of the
// header: neighbours outside the grid are the voxel itself, and the
// difference is divided by the distance actually spanned.
struct Grid {
    glm::ivec3 n;
    const std::vector<float>* f;
    double at(glm::ivec3 p) const {
        p = glm::clamp(p, glm::ivec3(0), n - 1);
        return (*f)[std::size_t(p.x) + std::size_t(n.x) * (std::size_t(p.y) + std::size_t(n.y) * p.z)];
    }
    // (f[+1] - f[-1]) / (number of voxel steps spanned), along `axis`.
    double difference(glm::ivec3 p, int axis) const {
        glm::ivec3 lo = p, hi = p;
        lo[axis] = std::max(p[axis] - 1, 0);
        hi[axis] = std::min(p[axis] + 1, n[axis] - 1);
        const int steps = hi[axis] - lo[axis];
        return steps == 0 ? 0.0 : (at(hi) - at(lo)) / steps;
    }
};

glm::vec3 gradientAt(const Grid& g, glm::ivec3 p, GradientEstimator e, glm::dvec3 perStep) {
    glm::dvec3 d(0.0);
    for (int axis = 0; axis < 3; ++axis) {
        if (e == GradientEstimator::Central) {
            d[axis] = g.difference(p, axis);
            continue;
        }
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        double sum = 0.0;
        for (int da = -1; da <= 1; ++da)
            for (int db = -1; db <= 1; ++db) {
                glm::ivec3 q = p;
                q[a] = std::clamp(p[a] + da, 0, g.n[a] - 1);
                q[b] = std::clamp(p[b] + db, 0, g.n[b] - 1);
                sum += (da == 0 ? 2 : 1) * (db == 0 ? 2 : 1) * g.difference(q, axis);
            }
        d[axis] = sum / 16.0;
    }
    return glm::vec3(d * perStep);
}

// Runs body(z) for every slice z, on all cores.
template <class F>
void forEachSlice(int slices, F body) {
    const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (int z = t; z < slices; z += threads) body(z);
        });
    for (auto& th : pool) th.join();
}

// The gradient volume and its float copy of the values take 16 bytes a
// voxel, up to 16 times the volume itself (24 GiB for the largest uint8
// volume the loaders accept), so they answer to the same cap.
void checkGradientMemory(const Volume& volume) {
    const std::uint64_t bytes = std::uint64_t(volume.voxelCount()) * (sizeof(glm::vec3) + sizeof(float));
    const std::uint64_t capMiB = volumeCapMiB();
    if (bytes <= capMiB << 20) return;
    const glm::ivec3 d = volume.dims();
    throw Error((volume.name().empty() ? std::string("volume") : volume.name()) + ": precomputed gradients of " +
                std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z) + " voxels take " +
                std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB, over the " + std::to_string(capMiB) +
                " MiB volume cap (set " + kVolumeCapVariable + " to raise it)");
}

}  // namespace

std::vector<glm::vec3> computeGradients(const Volume& volume, GradientEstimator estimator) {
    volume.requireInMemory("the precomputed gradient volume");
    checkGradientMemory(volume);
    const std::vector<float> values = valuesOf(volume);
    const Grid grid{volume.dims(), &values};
    // A difference per voxel step becomes one per unit length (the smallest
    // spacing) by the factor minSpacing / spacing.
    const glm::dvec3 perStep = volume.minSpacing() / volume.spacing();
    const glm::ivec3 n = volume.dims();
    std::vector<glm::vec3> out(volume.voxelCount());
    forEachSlice(n.z, [&](int k) {
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i)
                out[std::size_t(i) + std::size_t(n.x) * (std::size_t(j) + std::size_t(n.y) * k)] =
                    gradientAt(grid, {i, j, k}, estimator, perStep);
    });
    return out;
}

Histogram2D histogram2D(const Volume& volume, int valueBins, int gradientBins, GradientEstimator estimator) {
    Histogram2D h;
    h.valueLo = volume.minValue();
    h.valueHi = volume.maxValue();
    h.valueBins = std::max(valueBins, 1);
    h.gradientBins = std::max(gradientBins, 1);
    h.counts.assign(std::size_t(h.valueBins) * h.gradientBins, 0);
    const std::vector<glm::vec3> gradients = computeGradients(volume, estimator);
    std::vector<float> magnitude(gradients.size());
    for (std::size_t i = 0; i < gradients.size(); ++i) {
        magnitude[i] = glm::length(gradients[i]);
        h.gradientMax = std::max(h.gradientMax, double(magnitude[i]));
    }
    const auto bin = [](double x, double lo, double hi, int bins) {
        if (!(hi > lo)) return 0;
        return std::clamp(int((x - lo) / (hi - lo) * bins), 0, bins - 1);
    };
    for (std::size_t i = 0; i < magnitude.size(); ++i) {
        const int x = bin(volume.valueAt(i), h.valueLo, h.valueHi, h.valueBins);
        const int y = bin(magnitude[i], 0.0, h.gradientMax, h.gradientBins);
        ++h.counts[std::size_t(y) * h.valueBins + x];
    }
    return h;
}

}  // namespace voxlab
