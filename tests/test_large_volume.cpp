// Volumes of any size the data allows (issue 36): more than 2^31 voxels,
// and more than the memory cap, streamed from their file. Labelled heavy.
//
// The volume is a sparse raw file (NRRD, detached data) of 1300^3 uint8
// voxels, 2.2e9 of them, zero but for a few boxes whose voxels follow a
// known rule, so the oracle is the rule itself: the nearest MIP along +z is,
// at each pixel's voxel column, the largest value of the boxes over it. It
// is drawn by `voxlab render` in a child with a 512 MiB volume cap (so it is
// streamed, and drawn in bricks), and the child's peak resident memory
// (/usr/bin/time) must stay under half the volume.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "support/run_command.h"
#include "voxlab/image.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
constexpr int kSide = 1300;

struct Box {
    glm::ivec3 lo;
    int size;
};
const Box kBoxes[] = {{{100, 200, 10}, 64}, {{600, 600, 600}, 80}, {{640, 620, 1200}, 64},
                      {{1200, 40, 300}, 60}, {{5, 1220, 1230}, 50}};

std::uint8_t rule(int b, int x, int y, int z) { return std::uint8_t((x * 7 + y * 13 + z * 29 + b * 61) % 251 + 1); }

fs::path makeVolume() {
    const fs::path dir = fs::path(::testing::TempDir()) / ("voxlab_large_" + std::to_string(getpid()));
    fs::create_directories(dir);
    const fs::path raw = dir / "big.raw";
    const int fd = open(raw.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const std::uint64_t side = kSide;
    EXPECT_EQ(ftruncate(fd, off_t(side * side * side)), 0);
    std::vector<std::uint8_t> row;
    for (int b = 0; b < int(std::size(kBoxes)); ++b) {
        const Box& box = kBoxes[b];
        row.resize(std::size_t(box.size));
        for (int z = box.lo.z; z < box.lo.z + box.size; ++z)
            for (int y = box.lo.y; y < box.lo.y + box.size; ++y) {
                for (int x = 0; x < box.size; ++x) row[std::size_t(x)] = rule(b, box.lo.x + x, y, z);
                const std::uint64_t at = (std::uint64_t(z) * side + std::uint64_t(y)) * side + std::uint64_t(box.lo.x);
                EXPECT_EQ(pwrite(fd, row.data(), row.size(), off_t(at)), ssize_t(row.size()));
            }
    }
    close(fd);
    std::ofstream(dir / "big.nhdr") << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 1300 1300 1300\nencoding: raw\n"
                                       "data file: big.raw\n";
    return dir;
}

// The largest value over voxel column (x, y) along z: 0 outside the boxes.
int columnMax(int x, int y) {
    int best = 0;
    for (int b = 0; b < int(std::size(kBoxes)); ++b) {
        const Box& box = kBoxes[b];
        if (x < box.lo.x || y < box.lo.y || x >= box.lo.x + box.size || y >= box.lo.y + box.size) continue;
        for (int z = box.lo.z; z < box.lo.z + box.size; ++z) best = std::max(best, int(rule(b, x, y, z)));
    }
    return best;
}

TEST(LargeVolume, MoreThan2To31VoxelsStreamedAndDrawnInBricks) {
    const fs::path dir = makeVolume();
    // 520 pixels for 1300 voxels: each pixel centre falls inside one voxel.
    const int width = 520;
    const CommandResult r = runShell("/usr/bin/time -f 'maxrss %M kB' " + std::string(VOXLAB_BINARY) +
                                         " render --dataset " + (dir / "big.nhdr").string() +
                                         " --renderer mip --view +z --interpolation nearest --step 1 --size 520x520"
                                         " --max-volume-mib 512 --out " + (dir / "mip.png").string(),
                                     1200);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::size_t at = r.err.rfind("maxrss ");
    ASSERT_NE(at, std::string::npos) << r.err;
    const double peakMiB = std::atof(r.err.c_str() + at + 7) / 1024.0;
    std::cout << "peak resident memory of the render: " << peakMiB << " MiB for a 2095 MiB volume\n";
    EXPECT_LT(peakMiB, 2095.0 / 2) << "not streamed: the whole volume was resident";
    const Image image = loadPng((dir / "mip.png").string());
    // The grey scale runs over the volume's range: 0 (outside the boxes) to
    // the largest value in them.
    int hi = 0;
    for (int b = 0; b < int(std::size(kBoxes)); ++b)
        for (int y = 0; y < kBoxes[b].size; ++y)
            for (int x = 0; x < kBoxes[b].size; ++x)
                hi = std::max(hi, columnMax(kBoxes[b].lo.x + x, kBoxes[b].lo.y + y));
    int bad = 0, firstX = -1, firstY = -1, nonzero = 0;
    for (int py = 0; py < width; ++py)
        for (int px = 0; px < width; ++px) {
            const int x = int(std::floor((px + 0.5) * 2.5)), y = int(std::floor((py + 0.5) * 2.5));
            const int want = columnMax(x, y);
            nonzero += want > 0;
            const int got = toByte(image.at(px, py).r);
            const int wantGrey = int(std::lround(255.0 * want / hi));
            if (std::abs(got - wantGrey) > 1 && bad++ == 0) firstX = px, firstY = py;
        }
    EXPECT_GT(nonzero, 1000);
    EXPECT_EQ(bad, 0) << "first at pixel (" << firstX << ", " << firstY << ")";
    fs::remove_all(dir);
}

}  // namespace
}  // namespace voxlab::testing
