// voxlab: the coarser levels of a volume (see voxlab/volume_pyramid.h).
//
// Why the mean and not the maximum: the coarse level stands in for the
// volume under every renderer while the view moves (compositing, MIP,
// isosurfaces), and the mean keeps each region's typical value, so the
// transfer function shows the same materials; a maximum would grow every
// bright structure by a voxel per level.
#include "voxlab/volume_pyramid.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace voxlab {

namespace {

template <class T>
void store(std::vector<std::uint8_t>& bytes, std::size_t index, double value) {
    T v;
    if constexpr (std::is_floating_point_v<T>) v = T(value);
    else v = T(std::lround(value));
    std::memcpy(bytes.data() + index * sizeof(T), &v, sizeof(T));
}

}  // namespace

Volume halveVolume(const Volume& volume) {
    const glm::ivec3 d = volume.dims();
    glm::ivec3 h;
    for (int a = 0; a < 3; ++a) h[a] = d[a] > 1 ? (d[a] + 1) / 2 : 1;
    const VoxelType type = volume.type();
    std::vector<std::uint8_t> bytes(std::size_t(h.x) * std::size_t(h.y) * std::size_t(h.z) * voxelTypeSize(type));
    std::size_t out = 0;
    for (int k = 0; k < h.z; ++k)
        for (int j = 0; j < h.y; ++j)
            for (int i = 0; i < h.x; ++i, ++out) {
                glm::ivec3 first, last;
                for (int a = 0; a < 3; ++a) {
                    first[a] = d[a] > 1 ? glm::ivec3(i, j, k)[a] * 2 : 0;
                    last[a] = d[a] > 1 ? std::min(first[a] + 1, d[a] - 1) : 0;
                }
                double sum = 0.0;
                int n = 0;
                for (int z = first.z; z <= last.z; ++z)
                    for (int y = first.y; y <= last.y; ++y)
                        for (int x = first.x; x <= last.x; ++x, ++n) sum += volume.value(x, y, z);
                const double mean = sum / n;
                switch (type) {
                    case VoxelType::UInt8: store<std::uint8_t>(bytes, out, mean); break;
                    case VoxelType::UInt16: store<std::uint16_t>(bytes, out, mean); break;
                    case VoxelType::Int16: store<std::int16_t>(bytes, out, mean); break;
                    case VoxelType::Float32: store<float>(bytes, out, mean); break;
                }
            }
    const glm::dvec3 spacing = volume.extent() / glm::dvec3(h);
    return Volume(h, type, spacing, std::move(bytes), volume.name() + "@1/2");
}

int coarseLevelFor(glm::ivec3 dims, double voxels) {
    int level = 0;
    glm::dvec3 d(dims);
    while (d.x * d.y * d.z > voxels && glm::any(glm::greaterThan(d, glm::dvec3(1.0)))) {
        d = glm::max(glm::ceil(d / 2.0), glm::dvec3(1.0));
        ++level;
    }
    return level;
}

}  // namespace voxlab
