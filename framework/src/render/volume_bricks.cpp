// Planning the bricks of a volume and their visibility order (see
// voxlab/volume_bricks.h).
//
// Why split the axis with the largest bricks: a brick's apron costs
// 2 * kTextureBrickApron voxels per axis whatever its size, so bricks close to
// cubes waste the least memory on aprons and upload the fewest voxels twice.
#include "voxlab/volume_bricks.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <string>

#include "voxlab/error.h"

namespace voxlab {

namespace {

constexpr int kSmallestCore = 16;

std::size_t textureBytes(const glm::ivec3& size, int bytesPerVoxel) {
    return std::size_t(size.x) * std::size_t(size.y) * std::size_t(size.z) * std::size_t(bytesPerVoxel);
}

// The bricks for `count` bricks per axis.
BrickLayout layoutFor(const glm::ivec3& dims, const glm::ivec3& count, int bytesPerVoxel, int apron) {
    BrickLayout layout;
    layout.count = count;
    layout.core = (dims + count - 1) / count;
    for (int k = 0; k < count.z; ++k)
        for (int j = 0; j < count.y; ++j)
            for (int i = 0; i < count.x; ++i) {
                VolumeBrick b;
                b.lo = glm::ivec3(i, j, k) * layout.core;
                b.hi = glm::min(b.lo + layout.core, dims);
                b.textureOrigin = glm::max(b.lo - apron, glm::ivec3(0));
                b.textureSize = glm::min(b.hi + apron, dims) - b.textureOrigin;
                b.bytes = textureBytes(b.textureSize, bytesPerVoxel);
                layout.bricks.push_back(b);
            }
    return layout;
}

std::size_t largestBrick(const BrickLayout& layout) {
    std::size_t most = 0;
    for (const VolumeBrick& b : layout.bricks) most = std::max(most, b.bytes);
    return most;
}

bool fits(const BrickLayout& layout, int maxTextureSize, std::size_t budgetBytes) {
    for (const VolumeBrick& b : layout.bricks)
        if (b.textureSize.x > maxTextureSize || b.textureSize.y > maxTextureSize || b.textureSize.z > maxTextureSize)
            return false;
    return largestBrick(layout) <= budgetBytes;
}

// Fits, and either every brick stays on the GPU or at least `aimed` of
// them do at once.
bool fitsWithRoom(const BrickLayout& layout, int maxTextureSize, std::size_t budgetBytes, std::size_t aimed) {
    if (!fits(layout, maxTextureSize, budgetBytes)) return false;
    return layout.totalBytes() <= budgetBytes || largestBrick(layout) * aimed <= budgetBytes;
}

std::string mib(std::size_t bytes) { return std::to_string((bytes + (1u << 19)) >> 20) + " MiB"; }

}  // namespace

std::size_t BrickLayout::totalBytes() const {
    std::size_t total = 0;
    for (const VolumeBrick& b : bricks) total += b.bytes;
    return total;
}

std::size_t residentBricksAimed(std::size_t volumeBytes, std::size_t budgetBytes, bool passesExpensive) {
    return passesExpensive && volumeBytes > 2 * budgetBytes ? 1 : kResidentBricksAimed;
}

BrickLayout planBricks(const glm::ivec3& dims, int bytesPerVoxel, int maxTextureSize, std::size_t budgetBytes,
                       std::size_t aimedResident) {
    if (glm::any(glm::lessThan(dims, glm::ivec3(1)))) throw Error("bricks: the volume has no voxels");
    BrickLayout whole = layoutFor(dims, glm::ivec3(1), bytesPerVoxel, 0);
    whole.budgetBytes = budgetBytes;
    if (fits(whole, maxTextureSize, budgetBytes)) {
        whole.resident = 1;
        return whole;
    }
    glm::ivec3 count(1);
    for (;;) {
        BrickLayout layout = layoutFor(dims, count, bytesPerVoxel, kTextureBrickApron);
        // Split the axis whose bricks are longest (ties: the later axis,
        // the slowest in memory, so that uploads read longer rows).
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (layout.core[a] >= layout.core[axis]) axis = a;
        const bool smallest = layout.core[axis] <= kSmallestCore;
        if (fitsWithRoom(layout, maxTextureSize, budgetBytes, aimedResident) || (smallest && fits(layout, maxTextureSize, budgetBytes))) {
            layout.budgetBytes = budgetBytes;
            layout.resident = layout.totalBytes() <= budgetBytes
                                  ? layout.bricks.size()
                                  : std::max<std::size_t>(1, budgetBytes / largestBrick(layout));
            return layout;
        }
        if (smallest)
            throw Error("bricks: a GPU memory budget of " + mib(budgetBytes) + " cannot hold one brick of " +
                        std::to_string(kSmallestCore) + "^3 voxels with its apron (" +
                        mib(textureBytes(glm::ivec3(kSmallestCore + 2 * kTextureBrickApron), bytesPerVoxel)) +
                        "); give it more (--gpu-memory MIB)");
        ++count[axis];
    }
}

std::vector<int> frontToBackOrder(const BrickLayout& layout, const glm::dvec3& eye, const glm::dvec3& forward,
                                  bool orthographic) {
    const glm::ivec3 n = layout.count;
    std::vector<int> key(layout.bricks.size());
    for (std::size_t b = 0; b < layout.bricks.size(); ++b) {
        const glm::ivec3 index = layout.bricks[b].lo / glm::max(layout.core, glm::ivec3(1));
        int sum = 0;
        for (int a = 0; a < 3; ++a) {
            if (orthographic) {
                sum += forward[a] >= 0.0 ? index[a] : n[a] - 1 - index[a];
                continue;
            }
            // The eye's brick along this axis: -1 before the volume, n[a] past it.
            const double lo = double(layout.bricks.front().lo[a]);
            const double hi = double(layout.bricks.back().hi[a]);
            const int e = eye[a] < lo ? -1 : eye[a] >= hi ? n[a] : int(std::floor(eye[a] / layout.core[a]));
            sum += std::abs(index[a] - e);
        }
        key[b] = sum;
    }
    std::vector<int> order(layout.bricks.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
    return order;
}

}  // namespace voxlab
