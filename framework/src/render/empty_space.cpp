// voxlab: empty-space skipping, the CPU side (see empty_space.h).
#include "voxlab/empty_space.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "voxlab/error.h"
#include "voxlab/volume.h"

namespace voxlab {
namespace {

// Voxel `index` of raw little-endian voxels of type T, as a float.
template <class T>
float voxelValue(const std::uint8_t* bytes, std::size_t index) {
    T v;
    std::memcpy(&v, bytes + index * sizeof(T), sizeof(T));
    return float(v);
}

// Calls fill(T{}) with T the volume's voxel type.
template <class Fill>
void withVoxelType(VoxelType type, Fill&& fill) {
    switch (type) {
        case VoxelType::UInt8: fill(std::uint8_t{}); break;
        case VoxelType::UInt16: fill(std::uint16_t{}); break;
        case VoxelType::Int16: fill(std::int16_t{}); break;
        case VoxelType::Float32: fill(float{}); break;
    }
}

// The ranges, one layer of bricks (along z) at a time. First each voxel row
// of the layer (with its apron) is reduced to one (min, max) per brick
// column, then each brick combines the rows it covers. Every voxel is read
// about (B + 2A) / B times, and only one layer's rows are held at once
// (a few MiB for a 512^3 volume).
// A streamed volume's slices are let go once no later layer reads them
// (Volume::releaseSlices; nothing for a volume in memory).
template <class T>
void fillRanges(const Volume& volume, BrickGrid* grid) {
    const std::uint8_t* bytes = volume.bytes().data();
    const glm::ivec3 dims = volume.dims();
    const int b = grid->brickSize, apron = kBrickApron;
    const glm::ivec3 count = grid->count;
    const auto voxel = [&](std::size_t index) { return voxelValue<T>(bytes, index); };
    const auto first = [&](int brick) { return std::max(brick * b - apron, 0); };
    const auto last = [&](int brick, int n) { return std::min((brick + 1) * b + apron, n); };  // exclusive
    std::vector<glm::vec2> rows(std::size_t(b + 2 * apron) * std::size_t(dims.y) * std::size_t(count.x));
    for (int bz = 0; bz < count.z; ++bz) {
        const int z0 = first(bz), z1 = last(bz, dims.z);
        for (int z = z0; z < z1; ++z)
            for (int y = 0; y < dims.y; ++y) {
                const std::size_t row = (std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x);
                for (int bx = 0; bx < count.x; ++bx) {
                    glm::vec2 r(voxel(row + std::size_t(first(bx))));
                    for (int x = first(bx) + 1; x < last(bx, dims.x); ++x) {
                        const float v = voxel(row + std::size_t(x));
                        r = glm::vec2(std::min(r.x, v), std::max(r.y, v));
                    }
                    rows[(std::size_t(z - z0) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(count.x) +
                         std::size_t(bx)] = r;
                }
            }
        for (int by = 0; by < count.y; ++by)
            for (int bx = 0; bx < count.x; ++bx) {
                glm::vec2 r(INFINITY, -INFINITY);
                for (int z = z0; z < z1; ++z)
                    for (int y = first(by); y < last(by, dims.y); ++y) {
                        const glm::vec2 q = rows[(std::size_t(z - z0) * std::size_t(dims.y) + std::size_t(y)) *
                                                     std::size_t(count.x) +
                                                 std::size_t(bx)];
                        r = glm::vec2(std::min(r.x, q.x), std::max(r.y, q.y));
                    }
                grid->range[grid->index({bx, by, bz})] = r;
            }
        volume.releaseSlices(z0, std::min(z1, first(bz + 1)));
    }
}

// wideRange and gradientBound (see empty_space.h), brick by brick over
// the brick and kGradientApron voxels around it.
template <class T>
void fillGradientBounds(const Volume& volume, BrickGrid* grid) {
    const std::uint8_t* bytes = volume.bytes().data();
    const glm::ivec3 dims = volume.dims();
    constexpr int kGradientApron = 2;
    const auto at = [&](int x, int y, int z) {
        return double(voxelValue<T>(
            bytes, (std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x) + std::size_t(x)));
    };
    const int b = grid->brickSize;
    for (int bz = 0; bz < grid->count.z; ++bz, volume.releaseSlices(std::max((bz - 1) * b - kGradientApron, 0),
                                                                      std::max(bz * b - kGradientApron, 0)))
        for (int by = 0; by < grid->count.y; ++by)
            for (int bx = 0; bx < grid->count.x; ++bx) {
                const glm::ivec3 brick(bx, by, bz);
                const glm::ivec3 from = glm::max(brick * b - kGradientApron, glm::ivec3(0));
                const glm::ivec3 to = glm::min((brick + 1) * b + kGradientApron, dims);  // exclusive
                double lo = INFINITY, hi = -INFINITY;
                glm::dvec3 slope(0.0);
                for (int z = from.z; z < to.z; ++z)
                    for (int y = from.y; y < to.y; ++y)
                        for (int x = from.x; x < to.x; ++x) {
                            const double v = at(x, y, z);
                            lo = std::min(lo, v), hi = std::max(hi, v);
                            if (x + 1 < to.x) slope.x = std::max(slope.x, std::abs(at(x + 1, y, z) - v));
                            if (y + 1 < to.y) slope.y = std::max(slope.y, std::abs(at(x, y + 1, z) - v));
                            if (z + 1 < to.z) slope.z = std::max(slope.z, std::abs(at(x, y, z + 1) - v));
                        }
                const std::size_t i = grid->index(brick);
                grid->wideRange[i] = glm::vec2(float(lo), float(hi));
                // Rounded up a little: the shader's float arithmetic.
                grid->gradientBound[i] = float(glm::length(slope) * (1.0 + 1e-5) + 1e-6 * (std::abs(lo) + std::abs(hi)));
            }
}

// The largest |difference quotient| the central-difference stage can take
// where it reads voxel i along one axis of n voxels (see empty_space.h):
// |D(i)|, and near the faces also the one-voxel differences there. `at(k)`
// reads voxel k along the axis (clamped); `before` and `after` are voxels
// i - 1 and i + 1, read already.
template <class At>
double centralReach(const At& at, int i, int n, double before, double after) {
    double d = std::abs(after - before) * 0.5;
    if (i <= 1) d = std::max({d, std::abs(at(1) - at(0)), std::abs(at(2) - at(1))});
    if (i >= n - 2) d = std::max({d, std::abs(at(n - 1) - at(n - 2)), std::abs(at(n - 2) - at(n - 3))});
    return d;
}

// Per voxel column of one layer of bricks: the largest reach along each
// axis and the value range, over the layer's slices.
struct Column {
    glm::dvec3 reach{0.0};
    double lo = INFINITY, hi = -INFINITY;
};

// The tight bounds (empty_space.h) one layer of bricks at a time: each
// voxel of the layer's slices (with the apron) folded into its column, then
// each brick's columns folded together.
template <class T>
void fillTightGradientBounds(const Volume& volume, BrickGrid* grid, int apron) {
    const std::uint8_t* bytes = volume.bytes().data();
    const glm::ivec3 dims = volume.dims();
    const glm::dvec3 scale = volume.minSpacing() / volume.spacing();  // quotients per smallest spacing
    const auto at = [&](int x, int y, int z) {
        x = std::clamp(x, 0, dims.x - 1), y = std::clamp(y, 0, dims.y - 1), z = std::clamp(z, 0, dims.z - 1);
        return double(voxelValue<T>(
            bytes, (std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x) + std::size_t(x)));
    };
    const int b = grid->brickSize;
    const auto first = [&](int brick) { return std::max(brick * b - apron, 0); };
    const auto last = [&](int brick, int n) { return std::min((brick + 1) * b + apron, n); };  // exclusive
    std::vector<Column> columns(std::size_t(dims.x) * std::size_t(dims.y));
    for (int bz = 0; bz < grid->count.z; ++bz) {
        std::fill(columns.begin(), columns.end(), Column{});
        for (int z = first(bz); z < last(bz, dims.z); ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x) {
                    Column& c = columns[std::size_t(y) * std::size_t(dims.x) + std::size_t(x)];
                    // The voxel and the neighbours its differences read: the
                    // reach along each axis, and the values' spread for the
                    // filtering allowance.
                    const double v = at(x, y, z), xm = at(x - 1, y, z), xp = at(x + 1, y, z);
                    const double ym = at(x, y - 1, z), yp = at(x, y + 1, z), zm = at(x, y, z - 1), zp = at(x, y, z + 1);
                    c.lo = std::min({c.lo, v, xm, xp, ym, yp, zm, zp});
                    c.hi = std::max({c.hi, v, xm, xp, ym, yp, zm, zp});
                    const auto alongX = [&](int k) { return at(k, y, z); };
                    const auto alongY = [&](int k) { return at(x, k, z); };
                    const auto alongZ = [&](int k) { return at(x, y, k); };
                    c.reach.x = std::max(c.reach.x, centralReach(alongX, x, dims.x, xm, xp));
                    c.reach.y = std::max(c.reach.y, centralReach(alongY, y, dims.y, ym, yp));
                    c.reach.z = std::max(c.reach.z, centralReach(alongZ, z, dims.z, zm, zp));
                }
        for (int by = 0; by < grid->count.y; ++by)
            for (int bx = 0; bx < grid->count.x; ++bx) {
                Column all;
                for (int y = first(by); y < last(by, dims.y); ++y)
                    for (int x = first(bx); x < last(bx, dims.x); ++x) {
                        const Column& c = columns[std::size_t(y) * std::size_t(dims.x) + std::size_t(x)];
                        all.reach = glm::max(all.reach, c.reach);
                        all.lo = std::min(all.lo, c.lo), all.hi = std::max(all.hi, c.hi);
                    }
                const glm::dvec3 reach = (all.reach + (all.hi - all.lo) / 256.0) * scale;
                const std::size_t i = grid->index({bx, by, bz});
                grid->wideRange[i] = grid->range[i];
                // Rounded up a little: the shader's float arithmetic.
                grid->gradientBound[i] =
                    float(glm::length(reach) * (1.0 + 1e-5) + 1e-6 * (std::abs(all.lo) + std::abs(all.hi)));
            }
        // The next layer reads from one slice before its first (the differences).
        const int next = bz + 1 < grid->count.z ? std::max(first(bz + 1) - 1, first(bz)) : dims.z;
        volume.releaseSlices(first(bz), next);
    }
}

}  // namespace

void BrickGrid::computeGradientBounds(const Volume& volume, std::optional<GradientEstimator> estimator) {
    wideRange.assign(brickCount(), glm::vec2(0.0f));
    gradientBound.assign(brickCount(), 0.0f);
    boundsFor = estimator;
    withVoxelType(volume.type(), [&](auto voxel) {
        using T = decltype(voxel);
        if (!estimator) fillGradientBounds<T>(volume, this);
        // The 26-neighbour estimator's differences lie one voxel aside.
        else fillTightGradientBounds<T>(volume, this, *estimator == GradientEstimator::Sobel ? 2 : 1);
    });
}

int skippingBrickSize(const EmptySpaceRule& rule, glm::ivec3 dims) {
    if (rule.kind != EmptySpaceRule::Kind::TransferFunction2D) return kBrickSize;
    for (int size = 2; size < kBrickSize; size *= 2) {
        const glm::ivec3 n = (dims + size - 1) / size;
        if (std::size_t(n.x) * std::size_t(n.y) * std::size_t(n.z) <= kFineGridBricks) return size;
    }
    return kBrickSize;
}

BrickGrid BrickGrid::build(const Volume& volume, int brickSize) {
    BrickGrid grid;
    grid.brickSize = std::max(brickSize, 1);
    const glm::ivec3 dims = volume.dims();
    grid.count = (dims + grid.brickSize - 1) / grid.brickSize;
    grid.range.resize(std::size_t(grid.count.x) * std::size_t(grid.count.y) * std::size_t(grid.count.z));
    withVoxelType(volume.type(),
                  [&](auto voxel) { fillRanges<decltype(voxel)>(volume, &grid); });
    return grid;
}

glm::ivec3 BrickGrid::brickAt(glm::dvec3 voxelCoordinate) const {
    const glm::ivec3 b(glm::floor(voxelCoordinate / double(brickSize)));
    return glm::clamp(b, glm::ivec3(0), count - 1);
}

std::vector<std::uint8_t> visibleBricks(const BrickGrid& grid, const TransferFunctionTable& table) {
    const int size = table.size;
    if (size < 2) return std::vector<std::uint8_t>(grid.brickCount(), size == 1 && table.rgba[0].a > 0.0f);
    // opaqueBefore[i]: how many of the entries 0..i-1 have opacity > 0.
    std::vector<int> opaqueBefore(std::size_t(size) + 1, 0);
    for (int i = 0; i < size; ++i) opaqueBefore[i + 1] = opaqueBefore[i] + (table.rgba[i].a > 0.0f ? 1 : 0);
    // classify.glsl reads the two entries around x = (v - lo) / (hi - lo) * (size - 1),
    // weighted by how close x is to each: entries floor(x) .. ceil(x) carry weight. The
    // shader computes x in float, a few ulps off: the relative slack covers that, and x = 0
    // (the table's first value, often the air) stays exactly on entry 0.
    const double width = std::max(table.hi - table.lo, 1e-30);
    const auto position = [&](double v) { return std::clamp((v - table.lo) / width, 0.0, 1.0) * double(size - 1); };
    std::vector<std::uint8_t> visible(grid.brickCount());
    for (std::size_t i = 0; i < visible.size(); ++i) {
        const int from = std::max(int(std::floor(position(grid.range[i].x) * (1.0 - 1e-6))), 0);
        const int to = std::min(int(std::ceil(position(grid.range[i].y) * (1.0 + 1e-6))), size - 1);
        visible[i] = opaqueBefore[to + 1] - opaqueBefore[from] > 0;
    }
    return visible;
}

std::vector<std::uint8_t> visibleBricks(const BrickGrid& grid, const std::vector<Tf2dWidget>& widgets,
                                        double boundScale) {
    if (grid.gradientBound.size() != grid.brickCount())
        throw Error("empty-space skipping: the 2D transfer function needs the brick grid's gradient bounds "
                    "(BrickGrid::computeGradientBounds)");
    std::vector<std::uint8_t> visible(grid.brickCount(), 0);
    for (std::size_t i = 0; i < visible.size(); ++i) {
        const double lo = grid.wideRange[i].x, hi = grid.wideRange[i].y;
        const double gradientBound = boundScale * grid.gradientBound[i];
        for (const Tf2dWidget& w : widgets) {
            if (!(w.alpha > 0.0f)) continue;
            bool reaches;
            if (w.kind == Tf2dWidget::Kind::Box) {
                reaches = w.valueRange.x <= hi && w.valueRange.y >= lo && w.gradientRange.x <= gradientBound &&
                          w.gradientRange.y >= 0.0;
            } else {
                const double distance = std::max({0.0, lo - w.valueRange.x, w.valueRange.x - hi});
                reaches = distance <= w.radius * gradientBound;
            }
            if (reaches) {
                visible[i] = 1;
                break;
            }
        }
    }
    return visible;
}

std::vector<std::uint8_t> bricksReaching(const BrickGrid& grid, double threshold) {
    std::vector<std::uint8_t> visible(grid.brickCount());
    // The shader reads values as texel * scale + offset in float, which can
    // land an ulp or so above the stored value: a little slack below.
    const double t = threshold - 1e-5 * (std::abs(threshold) + 1.0);
    for (std::size_t i = 0; i < visible.size(); ++i) visible[i] = double(grid.range[i].y) >= t;
    return visible;
}

std::vector<std::uint8_t> allBricksVisible(const BrickGrid& grid) {
    return std::vector<std::uint8_t>(grid.brickCount(), 1);
}

}  // namespace voxlab
