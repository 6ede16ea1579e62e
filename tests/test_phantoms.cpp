// Analytic phantoms: each checked against its formula, computed here
// independently of the framework's implementation.
#include <gtest/gtest.h>

#include <cstring>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "voxlab/error.h"
#include "voxlab/phantoms.h"
#include "voxlab/volume.h"

using namespace voxlab;

namespace {

const double kPi = 3.14159265358979323846;

// Voxel centre i of n mapped to [-1, 1].
double unit(int i, int n) { return -1.0 + 2.0 * (i + 0.5) / n; }

std::string errorOf(const std::string& spec) {
    try {
        loadVolume(spec);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

// ct-signed, at voxels placed by its documented geometry (N = 64, centre
// 32): the bone core (r <= 16), fat (16 < r <= 25.6), tissue (25.6 < r <=
// 28.8), air outside, the air pocket of radius 5.12 around (52.48, 32, 32).
TEST(Phantoms, CtSignedHoldsItsHounsfieldUnits) {
    const Volume v = loadVolume("phantom:ct-signed:64");
    ASSERT_EQ(v.type(), VoxelType::Int16);
    auto at = [&](int i, int j, int k) {  // the stored bytes, not Volume::value
        std::int16_t x;
        std::memcpy(&x, v.bytes().data() + ((std::size_t(k) * 64 + j) * 64 + i) * 2, 2);
        return int(x);
    };
    EXPECT_EQ(at(32, 32, 32), 700);   // r = 0.87
    EXPECT_EQ(at(32, 32, 52), -100);  // r = 20.5
    EXPECT_EQ(at(32, 59, 32), 40);    // r = 27.5
    EXPECT_EQ(at(0, 0, 0), -1000);    // a corner
    EXPECT_EQ(at(52, 32, 32), -800);  // the pocket's centre, inside the fat
    EXPECT_EQ(at(32, 12, 32), -100);  // the other side: no pocket there
    EXPECT_EQ(v.minValue(), -1000.0);
    EXPECT_EQ(v.maxValue(), 700.0);
}

// The slab and the sphere at the voxel centres the formula puts them.
TEST(Phantoms, SphereOverSlab) {
    const Volume v = makePhantom("phantom:sphere-over-slab:40");
    const auto* f = static_cast<const float*>(v.data());
    auto at = [&](int i, int j, int k) { return f[i + 40 * (j + 40 * k)]; };
    EXPECT_EQ(at(0, 0, 4), 1.0f);     // z = 4.5, inside 4..10
    EXPECT_EQ(at(39, 39, 9), 1.0f);   // z = 9.5
    EXPECT_EQ(at(20, 20, 10), 0.0f);  // z = 10.5, above the slab
    EXPECT_EQ(at(20, 20, 24), 0.5f);  // the sphere's centre (20, 20, 24) is on a voxel corner
    EXPECT_EQ(at(20, 20, 29), 0.5f);  // 5.5 above the centre, radius 6
    EXPECT_EQ(at(20, 20, 30), 0.0f);  // 6.5 above
    EXPECT_EQ(at(3, 3, 24), 0.0f);    // beside it
}

TEST(Phantoms, NamesAndDefaults) {
    std::vector<std::string> names = phantomNames();
    for (const char* n : {"sphere", "shells", "marschner-lobb", "shepp-logan", "sphere-over-slab", "ramp-x", "ramp-y",
                          "ramp-z"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
    }
    for (const std::string& n : names) {
        Volume v = loadVolume("phantom:" + n);
        EXPECT_EQ(v.dims(), glm::ivec3(64)) << n;
        EXPECT_EQ(v.spacing(), glm::dvec3(1.0)) << n;
        EXPECT_EQ(v.name(), "phantom:" + n);
        EXPECT_EQ(v.type(), n == "shells"      ? VoxelType::UInt8
                            : n == "ct-signed" ? VoxelType::Int16
                                               : VoxelType::Float32)
            << n;
    }
    EXPECT_EQ(makePhantom("phantom:sphere:17").dims(), glm::ivec3(17));
    EXPECT_EQ(makePhantom("ramp-y:3").dims(), glm::ivec3(3));
}

TEST(Phantoms, SphereFollowsItsFormula) {
    const int n = 41;  // odd: voxel (20,20,20) sits exactly at the centre 20.5
    EXPECT_DOUBLE_EQ(spherePhantomRadius(n), 0.35 * 41);
    EXPECT_EQ(kSpherePhantomWidth, 4.0);
    Volume v = makePhantom("phantom:sphere:41");
    const double R = 0.35 * n, W = 4.0, c = n / 2.0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                double dx = i + 0.5 - c, dy = j + 0.5 - c, dz = k + 0.5 - c;
                double r = std::sqrt(dx * dx + dy * dy + dz * dz);
                double expected = std::min(1.0, std::max(0.0, 0.5 + (R - r) / W));
                ASSERT_NEAR(v.value(i, j, k), expected, 1e-6) << i << "," << j << "," << k;
            }
    EXPECT_EQ(v.value(20, 20, 20), 1.0);  // centre
    EXPECT_EQ(v.value(0, 0, 0), 0.0);     // background
    EXPECT_EQ(v.minValue(), 0.0);
    EXPECT_EQ(v.maxValue(), 1.0);
}

TEST(Phantoms, SphereHalfIsosurfaceIsAtRadiusR) {
    // The field is linear in r near the surface, so interpolating between
    // the two voxels on the x axis that straddle 0.5 lands exactly on R.
    const int n = 41;
    Volume v = makePhantom("phantom:sphere:41");
    const double R = spherePhantomRadius(n);
    const int inside = 20 + int(std::floor(R)), outside = inside + 1;
    double a = v.value(inside, 20, 20), b = v.value(outside, 20, 20);
    ASSERT_GT(a, 0.5);
    ASSERT_LT(b, 0.5);
    double crossing = (inside - 20) + (a - 0.5) / (a - b);
    EXPECT_NEAR(crossing, R, 1e-5);

    glm::dvec3 centre(n / 2.0);
    EXPECT_NEAR(spherePhantomValue(n, centre + R * glm::normalize(glm::dvec3(1, 2, -3))), 0.5, 1e-12);
    EXPECT_NEAR(spherePhantomValue(n, centre + (R + 1.0) * glm::dvec3(0, 0, 1)), 0.25, 1e-12);
}

TEST(Phantoms, ShellsFollowTheirFormula) {
    const int n = 64;
    Volume v = makePhantom("phantom:shells:64");
    const double c = n / 2.0, half = std::max(1.0, n / 16.0) / 2.0;
    const double radii[3] = {0.15 * n, 0.28 * n, 0.42 * n};
    const int values[3] = {80, 160, 240};
    std::uint64_t counts[3] = {0, 0, 0};
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                double dx = i + 0.5 - c, dy = j + 0.5 - c, dz = k + 0.5 - c;
                double r = std::sqrt(dx * dx + dy * dy + dz * dz);
                int expected = 0;
                for (int s = 0; s < 3; ++s) {
                    if (std::fabs(r - radii[s]) <= half) {
                        expected = values[s];
                        counts[s]++;
                    }
                }
                ASSERT_EQ(v.value(i, j, k), expected) << i << "," << j << "," << k;
            }
    for (std::uint64_t count : counts) EXPECT_GT(count, 0u);
    EXPECT_EQ(v.value(32, 32, 32), 0.0);
    EXPECT_EQ(v.value(0, 0, 0), 0.0);
    EXPECT_EQ(v.maxValue(), 240.0);
}

TEST(Phantoms, MarschnerLobbMatchesThePublishedFormula) {
    // Marschner & Lobb 1994, fM = 6, alpha = 0.25, on [-1,1]^3.
    for (int n : {41, 64}) {
        Volume v = makePhantom("phantom:marschner-lobb:" + std::to_string(n));
        const int probes[][3] = {{0, 0, 0}, {n / 2, n / 2, n / 2}, {n - 1, 3, 7}, {5, n - 2, n - 1},
                                 {n / 3, n / 4, n / 5}, {n - 1, n - 1, 0}, {11, 29, 17}};
        for (const auto& p : probes) {
            double x = unit(p[0], n), y = unit(p[1], n), z = unit(p[2], n);
            double r = std::sqrt(x * x + y * y);
            double rho = (1.0 - std::sin(kPi * z / 2.0) +
                          0.25 * (1.0 + std::cos(2.0 * kPi * 6.0 * std::cos(kPi * r / 2.0)))) /
                         (2.0 * 1.25);
            EXPECT_NEAR(v.value(p[0], p[1], p[2]), rho, 1e-6) << n << ": " << p[0] << "," << p[1] << "," << p[2];
        }
        EXPECT_GE(v.minValue(), 0.0);
        EXPECT_LE(v.maxValue(), 1.0);
    }
}

TEST(Phantoms, SheppLoganHead) {
    const int n = 128;
    Volume v = makePhantom("phantom:shepp-logan:128");
    auto at = [&](double x, double y, double z) {  // voxel whose centre is nearest (x,y,z)
        auto idx = [&](double q) { return int(std::lround((q + 1.0) * n / 2.0 - 0.5)); };
        return v.value(idx(x), idx(y), idx(z));
    };
    EXPECT_NEAR(at(0, 0, 0), 0.2, 1e-6);      // brain: skull 1.0 + brain -0.8
    EXPECT_NEAR(at(0, 0.89, 0), 1.0, 1e-6);   // skull, above the brain
    EXPECT_NEAR(at(0.22, 0, 0), 0.0, 1e-6);   // ventricle: 1 - 0.8 - 0.2
    EXPECT_NEAR(at(0, 0.35, -0.15), 0.3, 1e-6);  // a +0.1 feature inside the brain
    EXPECT_EQ(at(0.95, 0.95, 0.95), 0.0);     // outside the head
    for (int c = 0; c < 8; ++c) {
        EXPECT_EQ(v.value(c & 1 ? n - 1 : 0, c & 2 ? n - 1 : 0, c & 4 ? n - 1 : 0), 0.0);
    }
    EXPECT_GT(v.value(n / 2, n / 2, n / 2), 0.0);
    EXPECT_EQ(v.minValue(), 0.0);
    EXPECT_NEAR(v.maxValue(), 1.0, 1e-6);

    // The rasterised volume agrees with the point function everywhere.
    for (int k = 0; k < n; k += 3)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                ASSERT_NEAR(v.value(i, j, k), sheppLoganValue({unit(i, n), unit(j, n), unit(k, n)}), 1e-6)
                    << i << "," << j << "," << k;
}

TEST(Phantoms, Ramps) {
    Volume x = makePhantom("phantom:ramp-x:8"), y = makePhantom("phantom:ramp-y:8"),
           z = makePhantom("phantom:ramp-z:8");
    for (int k = 0; k < 8; ++k)
        for (int j = 0; j < 8; ++j)
            for (int i = 0; i < 8; ++i) {
                ASSERT_EQ(x.value(i, j, k), i + 0.5);
                ASSERT_EQ(y.value(i, j, k), j + 0.5);
                ASSERT_EQ(z.value(i, j, k), k + 0.5);
            }
}

TEST(Phantoms, Errors) {
    std::string m = errorOf("phantom:teapot");
    EXPECT_EQ(m.rfind("phantom:teapot: unknown phantom 'teapot' (known: sphere", 0), 0u) << m;
    m = errorOf("phantom:sphere:1");
    EXPECT_EQ(m, "phantom:sphere:1: size 1 is out of range (2..512)");
    m = errorOf("phantom:sphere:513");
    EXPECT_EQ(m, "phantom:sphere:513: size 513 is out of range (2..512)");
    m = errorOf("phantom:sphere:abc");
    EXPECT_EQ(m, "phantom:sphere:abc: invalid size 'abc' (need an integer 2..512)");
    m = errorOf("phantom:shells:");
    EXPECT_NE(m.find("invalid size ''"), std::string::npos) << m;

    auto start = std::chrono::steady_clock::now();
    m = errorOf("phantom:shepp-logan:100000");
    EXPECT_NE(m.find("size 100000 is out of range"), std::string::npos) << m;
    m = errorOf("phantom:shepp-logan:99999999999999999999");
    EXPECT_NE(m.find("invalid size"), std::string::npos) << m;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}
