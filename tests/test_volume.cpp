// Tests for voxlab::Volume: layout, value access, value range per voxel
// type, histogram and constructor validation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "voxlab/error.h"
#include "voxlab/volume.h"

using namespace voxlab;

namespace {

template <typename T>
std::vector<std::uint8_t> toBytes(const std::vector<T>& values) {
    std::vector<std::uint8_t> bytes(values.size() * sizeof(T));
    if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

template <typename T>
Volume makeVolume(glm::ivec3 dims, const std::vector<T>& values, VoxelType type,
                  glm::dvec3 spacing = glm::dvec3(1.0), std::string name = "") {
    return Volume(dims, type, spacing, toBytes(values), name);
}

// The message of the voxlab::Error thrown by f, or "" if none was thrown.
template <typename F>
std::string errorOf(F f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Volume, TypeNamesAndSizes) {
    EXPECT_STREQ(voxelTypeName(VoxelType::UInt8), "uint8");
    EXPECT_STREQ(voxelTypeName(VoxelType::UInt16), "uint16");
    EXPECT_STREQ(voxelTypeName(VoxelType::Int16), "int16");
    EXPECT_STREQ(voxelTypeName(VoxelType::Float32), "float32");
    EXPECT_EQ(voxelTypeSize(VoxelType::UInt8), 1u);
    EXPECT_EQ(voxelTypeSize(VoxelType::UInt16), 2u);
    EXPECT_EQ(voxelTypeSize(VoxelType::Int16), 2u);
    EXPECT_EQ(voxelTypeSize(VoxelType::Float32), 4u);
}

TEST(Volume, DefaultIsEmpty) {
    Volume v;
    EXPECT_EQ(v.voxelCount(), 0u);
    EXPECT_EQ(v.histogram(4).total(), 0u);
}

TEST(Volume, LayoutIsXFastest) {
    // value = i + 10 j + 100 k, stored at index i + nx*(j + ny*k).
    glm::ivec3 d(4, 3, 2);
    std::vector<std::uint16_t> values;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i) values.push_back(std::uint16_t(i + 10 * j + 100 * k));
    Volume v = makeVolume(d, values, VoxelType::UInt16, {0.5, 2.0, 3.0}, "layout");

    EXPECT_EQ(v.name(), "layout");
    EXPECT_EQ(v.dims(), d);
    EXPECT_EQ(v.voxelCount(), 24u);
    EXPECT_EQ(v.bytes().size(), 48u);
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i) EXPECT_EQ(v.value(i, j, k), i + 10 * j + 100 * k);
    EXPECT_EQ(v.valueAt(5), 11.0);  // i=1, j=1
    EXPECT_EQ(v.minValue(), 0.0);
    EXPECT_EQ(v.maxValue(), 123.0);
    EXPECT_EQ(v.extent(), glm::dvec3(2.0, 6.0, 6.0));
    EXPECT_EQ(v.minSpacing(), 0.5);
}

TEST(Volume, ValueRangeUInt8) {
    std::vector<std::uint8_t> values = {7, 0, 255, 128, 1, 254, 9, 10};
    Volume v = makeVolume(glm::ivec3(2, 2, 2), values, VoxelType::UInt8);
    EXPECT_EQ(v.minValue(), 0.0);
    EXPECT_EQ(v.maxValue(), 255.0);
    EXPECT_EQ(v.value(0, 1, 0), 255.0);
}

TEST(Volume, ValueRangeUInt16KeepsNativeValues) {
    std::vector<std::uint16_t> values = {4095, 300, 65535, 1000, 17, 40000, 2, 3};
    Volume v = makeVolume(glm::ivec3(2, 2, 2), values, VoxelType::UInt16);
    EXPECT_EQ(v.minValue(), 2.0);
    EXPECT_EQ(v.maxValue(), 65535.0);
    EXPECT_EQ(v.value(0, 0, 0), 4095.0);
    EXPECT_EQ(v.value(1, 0, 1), 40000.0);
}

TEST(Volume, ValueRangeInt16IsSigned) {
    std::vector<std::int16_t> values = {-1024, 0, 32767, -32768, 5, -5, 100, 3071};
    Volume v = makeVolume(glm::ivec3(8, 1, 1), values, VoxelType::Int16);
    EXPECT_EQ(v.minValue(), -32768.0);
    EXPECT_EQ(v.maxValue(), 32767.0);
    EXPECT_EQ(v.value(0, 0, 0), -1024.0);
    EXPECT_EQ(v.value(5, 0, 0), -5.0);
}

TEST(Volume, ValueRangeFloat32) {
    std::vector<float> values = {0.25f, -3.5f, 1e6f, 0.0f, -1e-3f, 2.0f};
    Volume v = makeVolume(glm::ivec3(1, 2, 3), values, VoxelType::Float32);
    EXPECT_EQ(v.minValue(), -3.5);
    EXPECT_EQ(v.maxValue(), 1e6);
    EXPECT_EQ(v.value(0, 0, 0), 0.25);
    EXPECT_FLOAT_EQ(v.value(0, 0, 2), -1e-3f);
}

TEST(Volume, HistogramBinsFollowTheDocumentedRule) {
    // Range [0, 10] in 5 bins of width 2: [0,2) [2,4) [4,6) [6,8) [8,10].
    std::vector<std::uint8_t> values = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 10};
    Volume v = makeVolume(glm::ivec3(12, 1, 1), values, VoxelType::UInt8);
    Histogram h = v.histogram(5);
    EXPECT_EQ(h.lo, 0.0);
    EXPECT_EQ(h.hi, 10.0);
    EXPECT_EQ(h.binWidth(), 2.0);
    ASSERT_EQ(h.counts.size(), 5u);
    EXPECT_EQ(h.counts, (std::vector<std::uint64_t>{2, 2, 2, 2, 4}));
    EXPECT_EQ(h.total(), 12u);
}

TEST(Volume, HistogramOfSignedAndFloatData) {
    std::vector<std::int16_t> s = {-100, -100, -50, 0, 50, 100};
    Histogram hs = makeVolume(glm::ivec3(6, 1, 1), s, VoxelType::Int16).histogram(4);
    EXPECT_EQ(hs.lo, -100.0);
    EXPECT_EQ(hs.hi, 100.0);
    EXPECT_EQ(hs.counts, (std::vector<std::uint64_t>{2, 1, 1, 2}));

    std::vector<float> f = {0.0f, 0.1f, 0.5f, 0.9f, 1.0f, 0.49f};
    Histogram hf = makeVolume(glm::ivec3(6, 1, 1), f, VoxelType::Float32).histogram(2);
    EXPECT_EQ(hf.counts, (std::vector<std::uint64_t>{3, 3}));

    std::vector<std::uint16_t> u = {0, 4095, 4095, 2048};
    Histogram hu = makeVolume(glm::ivec3(2, 2, 1), u, VoxelType::UInt16).histogram(256);
    EXPECT_EQ(hu.hi, 4095.0);
    EXPECT_EQ(hu.counts[0], 1u);
    EXPECT_EQ(hu.counts[255], 2u);
    EXPECT_EQ(hu.counts[128], 1u);  // 2048 / (4095/256) = 128.03
    EXPECT_EQ(hu.total(), 4u);
}

TEST(Volume, HistogramOfConstantVolumeUsesBinZero) {
    std::vector<std::uint8_t> values(8, 42);
    Histogram h = makeVolume(glm::ivec3(2, 2, 2), values, VoxelType::UInt8).histogram(16);
    EXPECT_EQ(h.lo, 42.0);
    EXPECT_EQ(h.hi, 42.0);
    EXPECT_EQ(h.counts[0], 8u);
    EXPECT_EQ(h.total(), 8u);
}

TEST(Volume, HistogramRejectsBadBinCount) {
    std::vector<std::uint8_t> values(8, 1);
    Volume v = makeVolume(glm::ivec3(2, 2, 2), values, VoxelType::UInt8);
    EXPECT_NE(errorOf([&] { v.histogram(0); }).find("bins"), std::string::npos);
}

TEST(Volume, RejectsNonPositiveDims) {
    std::string m = errorOf([] { Volume(glm::ivec3(0, 4, 4), VoxelType::UInt8, glm::dvec3(1), std::vector<std::uint8_t>{}, "v"); });
    EXPECT_NE(m.find("v: dimensions must be positive, got 0x4x4"), std::string::npos) << m;
    m = errorOf([] { Volume(glm::ivec3(2, -1, 4), VoxelType::UInt8, glm::dvec3(1), std::vector<std::uint8_t>{}); });
    EXPECT_NE(m.find("volume: dimensions must be positive"), std::string::npos) << m;
}

TEST(Volume, RejectsTooManyVoxelsBeforeLookingAtTheBytes) {
    // 2^45 voxels: past kMaxVoxels (2^44), refused from the sizes alone.
    std::string m = errorOf([] {
        Volume(glm::ivec3(32768, 32768, 32768), VoxelType::UInt8, glm::dvec3(1), std::vector<std::uint8_t>{});
    });
    EXPECT_NE(m.find("exceed the limit of 17592186044416 voxels"), std::string::npos) << m;
}

TEST(Volume, RejectsWrongByteCount) {
    std::string m = errorOf([] {
        Volume(glm::ivec3(2, 2, 2), VoxelType::UInt16, glm::dvec3(1), std::vector<std::uint8_t>(8), "short");
    });
    EXPECT_NE(m.find("short: voxel data has 8 bytes, expected 16"), std::string::npos) << m;
}

TEST(Volume, RejectsBadSpacing) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (glm::dvec3 s : {glm::dvec3(0, 1, 1), glm::dvec3(1, -2, 1), glm::dvec3(1, 1, nan),
                         glm::dvec3(inf, 1, 1)}) {
        std::string m = errorOf([&] {
            Volume(glm::ivec3(1, 1, 1), VoxelType::UInt8, s, std::vector<std::uint8_t>(1));
        });
        EXPECT_NE(m.find("spacing must be finite and positive"), std::string::npos) << m;
    }
}

TEST(Volume, RejectsNonFiniteFloatVoxels) {
    std::vector<float> values(8, 1.0f);
    values[1 + 2 * 1 + 4 * 1] = std::numeric_limits<float>::quiet_NaN();  // voxel (1,1,1)
    std::string m = errorOf([&] { makeVolume(glm::ivec3(2, 2, 2), values, VoxelType::Float32, glm::dvec3(1), "f"); });
    EXPECT_NE(m.find("f: float32 voxel (1, 1, 1) is NaN"), std::string::npos) << m;

    values[7] = 1.0f;
    values[2] = -std::numeric_limits<float>::infinity();  // voxel (0,1,0)
    m = errorOf([&] { makeVolume(glm::ivec3(2, 2, 2), values, VoxelType::Float32); });
    EXPECT_NE(m.find("float32 voxel (0, 1, 0) is infinite"), std::string::npos) << m;
}

TEST(Volume, ErrorsAreVoxlabErrorsOnOneLine) {
    try {
        Volume(glm::ivec3(1, 1, 1), VoxelType::Float32, glm::dvec3(1), std::vector<std::uint8_t>(3), "x");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
}
