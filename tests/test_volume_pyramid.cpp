// The coarse levels of a volume (voxlab/volume_pyramid.h), against the
// definition computed here voxel by voxel from the stored bytes: each coarse
// voxel the mean of the fine voxels whose indices halve to its own (2i and
// 2i+1 along each halved axis, 2i alone at the far end of an odd size),
// rounded for integer types; the box unchanged. The oracle reads the bytes
// itself rather than through Volume::value.
#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "voxlab/error.h"
#include "voxlab/volume.h"
#include "voxlab/volume_pyramid.h"

namespace voxlab::testing {
namespace {

template <class T>
Volume randomVolume(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing, unsigned seed, double lo, double hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> value(lo, hi);
    std::vector<std::uint8_t> bytes(std::size_t(dims.x) * dims.y * dims.z * sizeof(T));
    for (std::size_t i = 0; i < bytes.size() / sizeof(T); ++i) {
        const T v = std::is_floating_point_v<T> ? T(value(rng)) : T(std::floor(value(rng)));
        std::memcpy(&bytes[i * sizeof(T)], &v, sizeof(T));
    }
    return Volume(dims, type, spacing, std::move(bytes), "random");
}

template <class T>
T stored(const Volume& v, int x, int y, int z) {
    T t;
    const std::size_t i = (std::size_t(z) * v.dims().y + std::size_t(y)) * v.dims().x + std::size_t(x);
    std::memcpy(&t, v.bytes().data() + i * sizeof(T), sizeof(T));
    return t;
}

template <class T>
void expectHalved(const Volume& fine, double tolerance) {
    const Volume coarse = halveVolume(fine);
    const glm::ivec3 f = fine.dims(), c = coarse.dims();
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(c[a], f[a] == 1 ? 1 : (f[a] + 1) / 2) << "axis " << a;
        EXPECT_NEAR(c[a] * coarse.spacing()[a], f[a] * fine.spacing()[a], 1e-9) << "the box moved, axis " << a;
    }
    EXPECT_EQ(coarse.type(), fine.type());
    double worst = 0.0;
    for (int z = 0; z < c.z; ++z)
        for (int y = 0; y < c.y; ++y)
            for (int x = 0; x < c.x; ++x) {
                double sum = 0.0;
                int n = 0;
                for (int fz = 0; fz < f.z; ++fz)
                    for (int fy = 0; fy < f.y; ++fy)
                        for (int fx = 0; fx < f.x; ++fx) {
                            const bool mine = (f.x == 1 || fx / 2 == x) && (f.y == 1 || fy / 2 == y) &&
                                              (f.z == 1 || fz / 2 == z);
                            if (mine) sum += double(stored<T>(fine, fx, fy, fz)), ++n;
                        }
                const double expected = std::is_floating_point_v<T> ? sum / n : std::round(sum / n);
                worst = std::max(worst, std::abs(double(stored<T>(coarse, x, y, z)) - expected));
            }
    EXPECT_LE(worst, tolerance);
}

TEST(VolumePyramid, EachCoarseVoxelIsTheMeanOfItsBlock) {
    expectHalved<std::uint8_t>(randomVolume<std::uint8_t>({8, 6, 4}, VoxelType::UInt8, {1, 1, 1}, 1, 0, 256), 0.0);
    // Odd sizes: the last coarse voxel averages what is left.
    expectHalved<std::uint16_t>(randomVolume<std::uint16_t>({7, 5, 9}, VoxelType::UInt16, {0.5, 2, 1.25}, 2, 0, 65536),
                                0.0);
    expectHalved<std::int16_t>(randomVolume<std::int16_t>({9, 4, 3}, VoxelType::Int16, {1, 1, 3}, 3, -1024, 3071), 0.0);
    expectHalved<float>(randomVolume<float>({6, 7, 5}, VoxelType::Float32, {1, 1, 1}, 4, -1, 1), 1e-6);
    // A flat volume keeps its single slice.
    expectHalved<std::uint8_t>(randomVolume<std::uint8_t>({10, 6, 1}, VoxelType::UInt8, {1, 1, 1}, 5, 0, 256), 0.0);
}

TEST(VolumePyramid, TheMeanOfALinearRampSitsAtTheCoarseVoxelCentre) {
    // f = x (world units) on an even grid: each coarse voxel's mean is the
    // value at its own centre, so the levels keep the data where it was.
    const glm::ivec3 d(16, 4, 4);
    std::vector<std::uint8_t> bytes(std::size_t(d.x) * d.y * d.z * sizeof(float));
    for (int z = 0; z < d.z; ++z)
        for (int y = 0; y < d.y; ++y)
            for (int x = 0; x < d.x; ++x) {
                const float v = float((x + 0.5) * 0.75);
                std::memcpy(&bytes[((std::size_t(z) * d.y + y) * d.x + x) * sizeof(float)], &v, sizeof v);
            }
    const Volume fine(d, VoxelType::Float32, {0.75, 1, 1}, std::move(bytes), "ramp");
    const Volume coarse = halveVolume(halveVolume(fine));
    ASSERT_EQ(coarse.dims(), glm::ivec3(4, 1, 1));
    for (int x = 0; x < 4; ++x) EXPECT_NEAR(coarse.value(x, 0, 0), (x + 0.5) * coarse.spacing().x, 1e-5) << x;
}

TEST(VolumePyramid, TheCoarseLevelIsTheFirstWithinTheVoxelBudget) {
    const double budget = double(1 << 22);
    EXPECT_EQ(coarseLevelFor({128, 128, 128}, budget), 0);   // 2^21 voxels: small enough
    EXPECT_EQ(coarseLevelFor({256, 256, 256}, budget), 1);   // bonsai moves at 128^3
    EXPECT_EQ(coarseLevelFor({1024, 1024, 1024}, budget), 3);
    EXPECT_EQ(coarseLevelFor({2100, 128, 128}, budget), 2);  // 1050x64x64 is still 2^22.03
    EXPECT_EQ(coarseLevelFor({1, 1, 1}, 0.5), 0);            // nothing left to halve
}

}  // namespace
}  // namespace voxlab::testing
