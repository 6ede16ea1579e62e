// Memory caps on input: a file cannot make voxlab allocate more than the
// volume cap (volume.h), more than the data it really holds, or more than
// the caps on transfer functions and text inputs allow.
//
// Memory is measured honestly: loads that must stay small run in a forked
// child whose address space (RLIMIT_AS) may grow by only 1 GiB over what
// the process already maps, so that a declared-size allocation of several
// GiB, or a buffer that follows a stream past its declared size, ends in
// std::bad_alloc (or a kill) instead of the expected message.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/error_of.h"
#include "support/in_child.h"
#include "support/temp_dir.h"
#include "support/run_command.h"
#include "voxlab/error.h"
#include "voxlab/gradients.h"
#include "voxlab/scene.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"
#include "voxlab/viewer_script.h"
#include "voxlab/volume.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

constexpr std::uint64_t kMiB = std::uint64_t(1) << 20;
constexpr std::uint64_t kGiB = std::uint64_t(1) << 30;

// Sets (or, with nullptr, unsets) VOXLAB_MAX_VOLUME_MIB for one scope.
class CapVariable {
public:
    explicit CapVariable(const char* value) {
        const char* old = std::getenv("VOXLAB_MAX_VOLUME_MIB");
        if (old) old_ = old, hadOld_ = true;
        if (value) ::setenv("VOXLAB_MAX_VOLUME_MIB", value, 1);
        else ::unsetenv("VOXLAB_MAX_VOLUME_MIB");
    }
    ~CapVariable() {
        if (hadOld_) ::setenv("VOXLAB_MAX_VOLUME_MIB", old_.c_str(), 1);
        else ::unsetenv("VOXLAB_MAX_VOLUME_MIB");
    }

private:
    std::string old_;
    bool hadOld_ = false;
};

// A gzip member holding `data`.
std::string gzipped(const Bytes& data) {
    std::string out(compressBound(uLong(data.size())) + 64, '\0');
    z_stream zs{};
    deflateInit2(&zs, 1, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
    zs.next_in = const_cast<Bytef*>(data.data());
    zs.avail_in = uInt(data.size());
    zs.next_out = reinterpret_cast<Bytef*>(out.data());
    zs.avail_out = uInt(out.size());
    deflate(&zs, Z_FINISH);
    out.resize(zs.total_out);
    deflateEnd(&zs);
    return out;
}

// A gzip stream of `mib64` x 64 MiB of zeros, as that many concatenated
// members (the loader accepts them, as gzip(1) does): kilobytes on disk,
// gigabytes inflated, without the test ever holding them.
std::string zerosGzip(int mib64) {
    const std::string member = gzipped(Bytes(64 * kMiB, 0));
    std::string out;
    for (int i = 0; i < mib64; ++i) out += member;
    return out;
}

std::string nrrd(const std::string& type, const std::string& sizes, const std::string& encoding) {
    return "NRRD0004\ntype: " + type + "\ndimension: 3\nsizes: " + sizes + "\nencoding: " + encoding + "\n\n";
}

std::size_t mappedBytes() {
    std::ifstream statm("/proc/self/statm");
    std::size_t pages = 0;
    statm >> pages;
    return pages * std::size_t(::sysconf(_SC_PAGESIZE));
}

// Runs loadVolume(path) in a forked child that may map at most `headroom`
// bytes more than it does at the fork. Returns the voxlab::Error message,
// "loaded N bytes", "std::bad_alloc" or "killed by signal N".
std::string loadWithLimitedMemory(const std::string& path, std::uint64_t headroom = kGiB) {
    return messageInChild(
        [&] {
            const rlim_t limit = rlim_t(mappedBytes() + headroom);
            const struct rlimit r = {limit, limit};
            return ::setrlimit(RLIMIT_AS, &r) == 0;
        },
        [&] { return "loaded " + std::to_string(loadVolume(path).bytes().size()) + " bytes"; });
}

class InputCaps : public ::testing::Test {
protected:
    void SetUp() override {
        // Streaming caches (gzip over the cap) go here, not to ~/.cache.
        ::setenv("XDG_CACHE_HOME", (dir_ / "cache").c_str(), 1);
    }
    void TearDown() override {
        ::unsetenv("XDG_CACHE_HOME");
    }
    std::string write(const std::string& name, const std::string& text, const Bytes& data = {}) {
        return tmp_.write(name, text, data);
    }
    CapVariable defaultCap_{nullptr};  // every test starts from the default cap
    TempDir tmp_{"voxlab-caps"};
    const fs::path dir_ = tmp_.path();
};

// ---- the volume cap ---------------------------------------------------------------

TEST_F(InputCaps, DefaultCapIs4GiBAndIsCheckedBeforeAllocating) {
    EXPECT_EQ(volumeCapMiB(), 4096u);
    // 1024 x 1024 x 2048 float: 2^31 voxels, 8 GiB, over the cap. A raw NRRD
    // or .dat over the cap is streamed from its file rather than refused, so
    // its length is checked first; gzip is inflated into a cache file, which
    // ends as soon as the data does; a format that cannot be streamed (.fld)
    // is refused by the cap. All at once, in a process with little memory.
    const std::string gz = write("big.nrrd", nrrd("float", "1024 1024 2048", "gzip") + gzipped(Bytes(1000, 0)));
    const std::string raw = write("big_raw.nrrd", nrrd("float", "1024 1024 2048", "raw"), Bytes(10));
    write("big.raw", "", Bytes(10));
    const std::string dat = write("big.dat", "ObjectFileName: big.raw\nResolution: 1024 1024 2048\nFormat: FLOAT\n");
    const std::pair<std::string, std::string> cases[] = {
        {gz, ": truncated data: expected 8589934592 bytes, got 1000"},
        {raw, ": truncated data: expected 8589934592 bytes, got 10"},
        {dat, ": truncated data in 'big.raw': expected 8589934592 bytes, got 10"}};
    for (const auto& [path, expected] : cases) {
        const auto start = std::chrono::steady_clock::now();
        const std::string message = loadWithLimitedMemory(path);
        EXPECT_NE(message.find(expected), std::string::npos) << message;
        EXPECT_EQ(message.rfind(path, 0), 0u) << message;
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
    }
    // AVS fields hold at most 16-bit data, which stays within 4 GiB (2^31
    // voxels), so a lower cap.
    CapVariable cap("1024");
    const std::string fld = write("big.fld", "# AVS field file\nndim=3\ndim1=1024\ndim2=1024\ndim3=1024\nveclen=1\n"
                                             "data=short\nfield=uniform\n\f\f",
                                  Bytes(10));
    EXPECT_EQ(loadWithLimitedMemory(fld), fld + ": 1024x1024x1024 uint16 is 2048 MiB, over the 1024 MiB volume cap "
                                                "(set VOXLAB_MAX_VOLUME_MIB to raise it)");
}

// A single size of 2^31 (within kMaxVoxels, 2 GiB of uint8, under the cap)
// would wrap to a negative int after reading: refused from the header alone
// (found by a fuzzing helper: 2 MB of gzip used 3.1 GB before).
TEST_F(InputCaps, ASizeThatDoesNotFitAnIntIsRefusedFromTheHeader) {
    const std::string gz = write("wide.nrrd", nrrd("uchar", "2147483648 1 1", "gzip") + gzipped(Bytes(1000, 0)));
    const auto start = std::chrono::steady_clock::now();
    const std::string message = loadWithLimitedMemory(gz);
    EXPECT_NE(message.find("2147483648 1 1 exceed the limit"), std::string::npos) << message;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);
}

TEST_F(InputCaps, EnvironmentVariableLowersAndRaisesTheCap) {
    Bytes two(2 * kMiB), half(kMiB / 2);
    for (std::size_t i = 0; i < two.size(); ++i) two[i] = std::uint8_t(i * 7);
    for (std::size_t i = 0; i < half.size(); ++i) half[i] = std::uint8_t(i * 13);
    const std::string big = write("two.nrrd", nrrd("uchar", "128 128 128", "raw"), two);
    const std::string bigz = write("twoz.nrrd", nrrd("uchar", "128 128 128", "gzip") + gzipped(two));
    const std::string small = write("half.nrrd", nrrd("uchar", "64 64 128", "raw"), half);
    {
        CapVariable cap("1");
        EXPECT_EQ(volumeCapMiB(), 1u);
        // Over the cap: streamed, raw from its own file, gzip through a cache.
        for (const std::string& path : {big, bigz}) {
            const Volume v = loadVolume(path);
            EXPECT_TRUE(v.streamed()) << path;
            EXPECT_EQ(v.bytes(), two) << path;
        }
        EXPECT_EQ(loadVolume(small).bytes(), half);
        // Phantoms too: 64^3 float is exactly 1 MiB (allowed), 65^3 is not.
        EXPECT_EQ(loadVolume("phantom:sphere:64").bytes().size(), kMiB);
        EXPECT_EQ(errorOf([] { loadVolume("phantom:sphere:65"); }),
                  "phantom:sphere:65: 65x65x65 float32 is 1098500 bytes, over the 1 MiB volume cap (set "
                  "VOXLAB_MAX_VOLUME_MIB to raise it)");
    }
    {
        CapVariable cap("3");
        EXPECT_EQ(loadVolume(big).bytes(), two);
        EXPECT_EQ(loadVolume(bigz).bytes(), two);
    }
    for (const char* bad : {"0", "-1", "abc", "1.5", "1048577", "99999999999999999999", "2\nx"}) {
        CapVariable cap(bad);
        const std::string message = errorOf([&] { loadVolume(small); });
        EXPECT_EQ(message.rfind("VOXLAB_MAX_VOLUME_MIB: expected a whole number of MiB from 1 to 1048576, got '", 0),
                  0u)
            << bad << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    CapVariable empty("");  // set but empty: the default
    EXPECT_EQ(volumeCapMiB(), 4096u);
}

TEST_F(InputCaps, CommandLineOptionSetsTheCap) {
    // A raw NRRD over the cap is streamed from its file, one in it is read.
    const std::string big = write("two.nrrd", nrrd("uchar", "128 128 128", "raw"), Bytes(2 * kMiB, 1));
    const CommandResult streamed = runVoxlab("info " + big + " --max-volume-mib 1");
    EXPECT_EQ(streamed.exitCode, 0) << streamed.err;
    EXPECT_NE(streamed.out.find("storage:  streamed from " + big + " (over the 1 MiB volume cap"), std::string::npos)
        << streamed.out;
    EXPECT_NE(runShell("env VOXLAB_MAX_VOLUME_MIB=1 " + std::string(VOXLAB_BINARY) + " info " + big).out.find("streamed"),
              std::string::npos);
    const CommandResult allowed = runVoxlab("info " + big + " --max-volume-mib 2");
    EXPECT_EQ(allowed.exitCode, 0) << allowed.err;
    EXPECT_EQ(allowed.out.find("streamed"), std::string::npos) << allowed.out;
    const CommandResult render = runVoxlab("render --dataset phantom:sphere:128 --max-volume-mib 1 --out " +
                                           (dir_ / "x.png").string());
    EXPECT_NE(render.exitCode, 0);
    EXPECT_NE(render.err.find("phantom:sphere:128: 128x128x128 float32 is 8 MiB, over the 1 MiB volume cap"),
              std::string::npos)
        << render.err;
    EXPECT_FALSE(fs::exists(dir_ / "x.png"));
    const CommandResult bad = runVoxlab("info " + big + " --max-volume-mib lots");
    EXPECT_EQ(bad.err, "voxlab: option --max-volume-mib: expected a whole number of MiB from 1 to 1048576, got "
                       "'lots'\n");
}

// Precomputed gradients take 16 bytes a voxel (12 for the gradient, 4 for a
// float copy of the values): the cap covers them too.
TEST_F(InputCaps, PrecomputedGradientsAnswerToTheCap) {
    CapVariable cap("1");
    const Volume small(glm::ivec3(32), VoxelType::UInt8, glm::dvec3(1.0), Bytes(32 * 32 * 32, 1), "small");
    EXPECT_EQ(computeGradients(small, GradientEstimator::Central).size(), 32u * 32 * 32);  // 512 KiB
    const Volume big(glm::ivec3(64), VoxelType::UInt8, glm::dvec3(1.0), Bytes(64 * 64 * 64, 1), "big");
    EXPECT_EQ(errorOf([&] { computeGradients(big, GradientEstimator::Sobel); }),
              "big: precomputed gradients of 64x64x64 voxels take 4 MiB, over the 1 MiB volume cap (set "
              "VOXLAB_MAX_VOLUME_MIB to raise it)");
}

// ---- data that is not there -------------------------------------------------------

// 1024 x 1024 x 1536 uint16 is 3 GiB: under the cap, so only the file's real
// size can stop the allocation. Raw data is checked against it first.
TEST_F(InputCaps, TruncatedRawDataIsRefusedWithoutADeclaredSizeAllocation) {
    const std::string message = "truncated data: expected 3221225472 bytes, got 10";
    const std::string attached = write("a.nrrd", nrrd("ushort", "1024 1024 1536", "raw"), Bytes(10));
    EXPECT_EQ(loadWithLimitedMemory(attached), attached + ": " + message);
    write("d.raw", "", Bytes(10));
    const std::string detached = write("d.nhdr", "NRRD0004\ntype: ushort\ndimension: 3\nsizes: 1024 1024 1536\n"
                                                 "encoding: raw\ndata file: d.raw\n");
    EXPECT_EQ(loadWithLimitedMemory(detached), detached + ": truncated data in 'd.raw': expected 3221225472 bytes, got 10");
    const std::string dat = write("v.dat", "ObjectFileName: d.raw\nResolution: 1024 1024 1536\nFormat: USHORT\n");
    EXPECT_EQ(loadWithLimitedMemory(dat), dat + ": truncated data in 'd.raw': expected 3221225472 bytes, got 10");
    const std::string fld = write("v.fld", "# AVS field file\nndim=3\ndim1=1024\ndim2=1024\ndim3=1536\nveclen=1\n"
                                           "data=short\nfield=uniform\n\f\f",
                                  Bytes(10));
    EXPECT_EQ(loadWithLimitedMemory(fld), fld + ": " + message);
}

// A gzip stream costs what it holds, not what it declares: 1 KiB, then 192
// MiB of real data, against 3 GiB declared.
TEST_F(InputCaps, ShortGzipStreamCostsOnlyWhatItHolds) {
    const std::string tiny = write("tiny.nrrd", nrrd("ushort", "1024 1024 1536", "gzip") + gzipped(Bytes(1024, 5)));
    EXPECT_EQ(loadWithLimitedMemory(tiny), tiny + ": truncated data: expected 3221225472 bytes, got 1024");
    const std::string part = write("part.nrrd", nrrd("ushort", "1024 1024 1536", "gzip") + zerosGzip(3));
    EXPECT_EQ(loadWithLimitedMemory(part), part + ": truncated data: expected 3221225472 bytes, got 201326592");
}

// A stream that inflates to 2 GiB behind an 8 MiB header stops at the first
// byte past 8 MiB; a buffer following the stream would need 2 GiB.
TEST_F(InputCaps, GzipStreamLongerThanDeclaredIsStoppedAtTheDeclaredSize) {
    const std::string path = write("bomb.nrrd", nrrd("uchar", "256 256 128", "gzip") + zerosGzip(32));
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(loadWithLimitedMemory(path, 256 * kMiB), path + ": gzip data is too long: more than 8388608 bytes");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

// ---- transfer functions -----------------------------------------------------------

nlohmann::json points(std::size_t n) {
    nlohmann::json arr = nlohmann::json::array();
    for (std::size_t i = 0; i < n; ++i)
        arr.push_back({{"value", double(i)}, {"color", {0.25, 0.5, 1.0}}, {"alpha", 0.5}});
    return arr;
}

TEST_F(InputCaps, TransferFunctionPointCap) {
    EXPECT_EQ(kMaxTransferFunctionPoints, 65536u);
    // The largest allowed function, written as the editor writes it (dump(2)),
    // loads: the cap on text inputs leaves room for it.
    const std::string most = write("most.json", points(65536).dump(2));
    EXPECT_LT(fs::file_size(most), 16 * kMiB);
    EXPECT_EQ(TransferFunction::load(most).points().size(), 65536u);

    const std::string over = write("over.json", points(65537).dump());
    EXPECT_EQ(errorOf([&] { TransferFunction::load(over); }),
              over + ": points: 65537 control points (at most 65536)");
    const std::string wrapped = write("wrapped.json", nlohmann::json{{"points", points(65537)}}.dump());
    EXPECT_EQ(errorOf([&] { TransferFunction::load(wrapped); }),
              wrapped + ": points: 65537 control points (at most 65536)");
    const std::string scene =
        write("scene.json", nlohmann::json{{"dataset", "phantom:sphere:8"}, {"transfer_function", points(65537)}}.dump());
    EXPECT_NE(errorOf([&] { Scene::load(scene); }).find("transfer_function: 65537 control points (at most 65536)"),
              std::string::npos);
    EXPECT_EQ(errorOf([] {
                  TransferFunction(std::vector<ControlPoint>(65537, ControlPoint{0.0, glm::vec3(0.0f), 0.0f}));
              }),
              "transfer function: 65537 control points (at most 65536)");
}

TEST_F(InputCaps, TransferFunction2DWidgetCap) {
    nlohmann::json widgets = nlohmann::json::array();
    for (int i = 0; i <= kMaxTf2dWidgets; ++i)
        widgets.push_back({{"type", "triangle"}, {"value", 10}, {"radius", 1}, {"alpha", 0.5}, {"color", {1, 1, 1}}});
    const std::string path = write("tf2d.json", nlohmann::json{{"widgets", widgets}}.dump());
    EXPECT_EQ(errorOf([&] { TransferFunction2D::load(path); }),
              path + ": widgets: " + std::to_string(kMaxTf2dWidgets + 1) + " widgets (at most " +
                  std::to_string(kMaxTf2dWidgets) + ")");
}

// ---- text inputs ------------------------------------------------------------------

TEST_F(InputCaps, TextInputsOver16MiBAreRefusedBeforeParsing) {
    // Valid JSON of 16 MiB + 1 byte: an array of zeros, padded with spaces.
    std::string text = "[0" + std::string(16 * kMiB - 3, ' ') + "]";
    ASSERT_EQ(text.size(), 16 * kMiB);
    const std::string atLimit = write("limit.json", text);
    EXPECT_EQ(errorOf([&] { TransferFunction::load(atLimit); }), atLimit + ": points[0]: expected an object "
                                                                           "{\"value\", \"color\", \"alpha\"}");
    const std::string over = write("over.json", text + " ");
    const std::string message = over + ": more than 16 MiB (the limit for a text input)";
    EXPECT_EQ(errorOf([&] { TransferFunction::load(over); }), message);
    EXPECT_EQ(errorOf([&] { TransferFunction2D::load(over); }), message);
    EXPECT_EQ(errorOf([&] { Scene::load(over); }), message);
    EXPECT_EQ(errorOf([&] { parseViewerScript(over); }), message);

    // A sparse 64 GiB file is refused by its size, without reading it.
    const fs::path huge = dir_ / "huge.json";
    std::ofstream(huge).put('[');
    fs::resize_file(huge, 64 * kGiB);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(errorOf([&] { Scene::load(huge.string()); }),
              huge.string() + ": more than 16 MiB (the limit for a text input)");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    // Not a regular file: read up to the limit, then refused.
    EXPECT_EQ(errorOf([] { Scene::load("/dev/zero"); }), "/dev/zero: more than 16 MiB (the limit for a text input)");
}

}  // namespace
}  // namespace voxlab::testing
