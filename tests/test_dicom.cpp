// The DICOM loader (framework/src/volume/dicom_loader.cpp) against series
// written by an independent tool: tests/dicom/make_series.py, which uses
// pydicom under Debian's /usr/bin/python3. Each series stores
// stored(i, j, k) = i + 10*j + 100*k + BASE at column i, row j and slice k
// (k counted along the slice normal), with a Rescale Slope and Intercept, so
// every voxel's expected value is known here without reading the files.
// The files are written shuffled, with misleading Instance Numbers.
// A missing pydicom fails every test (the script exits 3); nothing is skipped.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

#include "support/run_command.h"
#include "voxlab/error.h"
#include "voxlab/volume.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

const std::string kPython = "/usr/bin/python3";
const std::string kMakeSeries = std::string(VOXLAB_SOURCE_DIR) + "/tests/dicom/make_series.py";

class Dicom : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("voxlab_dicom_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Writes a series into a new folder `name` with make_series.py's options;
    // returns the folder. A failure of the script (no pydicom) fails the test.
    std::string series(const std::string& name, const std::string& options = "") {
        const std::string out = (dir_ / name).string();
        const CommandResult r = runShell(kPython + " " + kMakeSeries + " " + out + " " + options);
        if (r.exitCode != 0) {
            ADD_FAILURE() << "make_series.py " << options << " failed (exit " << r.exitCode << "): " << r.err;
            throw std::runtime_error("no series");
        }
        return out;
    }

    // Expects loadVolume(path) to fail with one line starting with the path
    // and holding each of `phrases`.
    void expectError(const std::string& path, std::initializer_list<std::string> phrases) {
        std::string message;
        try {
            loadVolume(path);
            ADD_FAILURE() << "no error for " << path;
            return;
        } catch (const Error& e) {
            message = e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << "not a voxlab::Error: " << e.what();
            return;
        }
        std::cout << "    message: " << message << "\n";
        EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        for (const std::string& phrase : phrases)
            EXPECT_NE(message.find(phrase), std::string::npos) << "expected '" << phrase << "' in: " << message;
    }

    fs::path dir_;
};

// Every voxel equals expected(i, j, k).
void expectVoxels(const Volume& v, glm::ivec3 dims, const std::function<double(int, int, int)>& expected) {
    ASSERT_EQ(v.dims(), dims);
    int wrong = 0;
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i)
                if (v.value(i, j, k) != expected(i, j, k) && ++wrong <= 5)
                    ADD_FAILURE() << "voxel (" << i << "," << j << "," << k << ") is " << v.value(i, j, k)
                                  << ", expected " << expected(i, j, k);
    EXPECT_EQ(wrong, 0);
}

std::string metadata(const Volume& v, const std::string& key) {
    for (const auto& [k, value] : v.metadata())
        if (k == key) return value;
    return "(no " + key + ")";
}

double stored(int i, int j, int k) { return i + 10 * j + 100 * k; }

TEST_F(Dicom, PydicomIsInstalledForDebiansPython) {
    const CommandResult r = runShell(kPython + " -c 'import pydicom, numpy; print(pydicom.__version__)'");
    ASSERT_EQ(r.exitCode, 0) << "python3-pydicom is missing for " << kPython
                             << " (apt-get install python3-pydicom python3-numpy): " << r.err;
}

// ---- voxels, order, spacing ---------------------------------------------------------

TEST_F(Dicom, KnownVoxelsThroughSlopeAndIntercept) {
    const std::string dir = series("ct", "--cols 5 --rows 4 --slices 6 --base 24 --slope 1 --intercept -1024");
    const Volume v = loadVolume(dir);
    EXPECT_EQ(v.type(), VoxelType::Int16);
    EXPECT_EQ(v.name(), "ct");
    expectVoxels(v, {5, 4, 6}, [](int i, int j, int k) { return i + 10 * j + 100 * k - 1000; });
    EXPECT_EQ(v.spacing(), glm::dvec3(1.0));
    EXPECT_EQ(metadata(v, "series"), "voxlab test series");
    EXPECT_EQ(metadata(v, "modality"), "CT");
    EXPECT_EQ(metadata(v, "slices").rfind("6 files", 0), 0u) << metadata(v, "slices");
    EXPECT_EQ(metadata(v, "orientation").rfind("axial: +x = L, +y = P, +z = S", 0), 0u)
        << metadata(v, "orientation");
    EXPECT_NE(metadata(v, "rescale").find("value = 1 x stored - 1024 in HU, as int16"), std::string::npos)
        << metadata(v, "rescale");
}

// Files named and numbered in a shuffled order: only the positions tell.
TEST_F(Dicom, SliceOrderComesFromPositionsNotNamesOrInstanceNumbers) {
    for (const char* order : {"shuffled", "ascending", "descending"}) {
        SCOPED_TRACE(order);
        const std::string dir = series(order, std::string("--slices 12 --seed 5 --order ") + order);
        expectVoxels(loadVolume(dir), {5, 4, 12}, stored);
    }
}

// Pixel Spacing (0028,0030) is [row spacing, column spacing] = [y, x]; the
// slice spacing comes from the positions (Slice Thickness says otherwise).
TEST_F(Dicom, SpacingFromPixelSpacingAndPositions) {
    const std::string dir = series("aniso", "--pixel-spacing 0.7 0.3 --spacing 2.5 --slices 4");
    const Volume v = loadVolume(dir);
    EXPECT_DOUBLE_EQ(v.spacing().x, 0.3);
    EXPECT_DOUBLE_EQ(v.spacing().y, 0.7);
    EXPECT_NEAR(v.spacing().z, 2.5, 1e-12);
    expectVoxels(v, {5, 4, 4}, stored);
}

// A normal pointing to the feet (column cosine towards anterior): positions
// fall along z while k grows; slice k is still the k-th along the normal.
TEST_F(Dicom, DescendingPositionsAlongAFlippedNormal) {
    const std::string dir = series("feet", "--orientation 1 0 0 0 -1 0 --spacing 2 --slices 5 --order ascending");
    const Volume v = loadVolume(dir);
    expectVoxels(v, {5, 4, 5}, stored);
    EXPECT_NEAR(v.spacing().z, 2.0, 1e-12);
    EXPECT_EQ(metadata(v, "orientation").rfind("axial: +x = L, +y = A, +z = I", 0), 0u)
        << metadata(v, "orientation");
}

TEST_F(Dicom, ObliqueSeriesLoadsOnItsOwnAxes) {
    const double c = std::cos(0.3), s = std::sin(0.3);  // tilted 17.2 degrees about x
    const std::string dir = series("oblique", "--orientation 1 0 0 0 " + std::to_string(c) + " " +
                                                  std::to_string(s) + " --spacing 1.5 --slices 4");
    const Volume v = loadVolume(dir);
    expectVoxels(v, {5, 4, 4}, stored);
    EXPECT_NEAR(v.spacing().z, 1.5, 1e-5);
    EXPECT_EQ(metadata(v, "orientation").rfind("oblique (17.1887 deg from axial)", 0), 0u)
        << metadata(v, "orientation");
    EXPECT_NE(metadata(v, "orientation").find("own axes"), std::string::npos);
}

// ---- value types -----------------------------------------------------------------------

TEST_F(Dicom, SignedAndUnsigned16BitWithoutRescale) {
    const Volume s = loadVolume(series("signed", "--stored int16 --base -500 --no-rescale"));
    EXPECT_EQ(s.type(), VoxelType::Int16);
    expectVoxels(s, {5, 4, 3}, [](int i, int j, int k) { return stored(i, j, k) - 500; });
    EXPECT_NE(metadata(s, "rescale").find("none"), std::string::npos) << metadata(s, "rescale");

    const Volume u = loadVolume(series("unsigned", "--stored uint16 --base 40000 --slope 1 --intercept 0"));
    EXPECT_EQ(u.type(), VoxelType::UInt16);
    expectVoxels(u, {5, 4, 3}, [](int i, int j, int k) { return stored(i, j, k) + 40000; });

    // 12 of 16 bits stored, the 4 above them set: those bits are not data.
    const Volume b12 = loadVolume(series("bits12", "--stored uint16 --bits-stored 12 --base 1000 --no-rescale"));
    EXPECT_EQ(b12.type(), VoxelType::UInt16);
    expectVoxels(b12, {5, 4, 3}, [](int i, int j, int k) { return stored(i, j, k) + 1000; });

    const Volume u8 = loadVolume(series("bytes", "--stored uint8 --slices 2 --no-rescale"));
    EXPECT_EQ(u8.type(), VoxelType::UInt8);
    expectVoxels(u8, {5, 4, 2}, stored);
}

TEST_F(Dicom, SlopeTwoInterceptMinus1024GivesHounsfieldUnits) {
    const Volume v = loadVolume(series("hu", "--stored uint16 --base 0 --slope 2 --intercept -1024"));
    EXPECT_EQ(v.type(), VoxelType::Int16);
    expectVoxels(v, {5, 4, 3}, [](int i, int j, int k) { return 2 * stored(i, j, k) - 1024; });
    EXPECT_NE(metadata(v, "rescale").find("value = 2 x stored - 1024 in HU"), std::string::npos)
        << metadata(v, "rescale");
}

TEST_F(Dicom, NonIntegerOrOutOfRangeValuesBecomeFloat32) {
    const Volume half = loadVolume(series("half", "--slope 0.5 --intercept 0.25"));
    EXPECT_EQ(half.type(), VoxelType::Float32);
    expectVoxels(half, {5, 4, 3}, [](int i, int j, int k) { return 0.5 * stored(i, j, k) + 0.25; });

    const Volume big = loadVolume(series("big", "--stored uint16 --base 40000 --slope 1 --intercept -1"));
    EXPECT_EQ(big.type(), VoxelType::Float32);  // 39999.. is an integer beyond int16
    expectVoxels(big, {5, 4, 3}, [](int i, int j, int k) { return stored(i, j, k) + 39999; });
}

TEST_F(Dicom, EncodingsAndFileNames) {
    expectVoxels(loadVolume(series("be", "--big-endian --stored uint16 --base 7")), {5, 4, 3},
                 [](int i, int j, int k) { return stored(i, j, k) + 7; });
    // Implicit VR without the preamble and "DICM": found through the folder.
    expectVoxels(loadVolume(series("implicit", "--implicit --no-preamble --extension .IMA")), {5, 4, 3}, stored);
    // No extension: found by "DICM" at byte 128, as one file of the series.
    const std::string noext = series("noext", "--extension '' --order ascending");
    expectVoxels(loadVolume(noext + "/IM001"), {5, 4, 3}, stored);
    // A file that is not DICOM in the folder is skipped.
    expectVoxels(loadVolume(series("readme", "--extra-file")), {5, 4, 3}, stored);
}

// One file names its series among others in the same folder.
TEST_F(Dicom, OneFileChoosesItsSeries) {
    const std::string dir = series("two", "--second-series --slices 4");
    expectVoxels(loadVolume(dir + "/IM002.dcm"), {5, 4, 4}, stored);
    expectVoxels(loadVolume(dir + "/SE2_001.dcm"), {5, 4, 2}, stored);
}

// The bundled headsq.nrrd written as DICOM by tools/nrrd_to_dicom.py (its own
// NRRD reader, pydicom's writer) loads as the same volume.
TEST_F(Dicom, HeadsqThroughDicomEqualsTheNrrd) {
    const std::string out = (dir_ / "headsq").string();
    const CommandResult r = runShell(kPython + " " + VOXLAB_SOURCE_DIR + "/tools/nrrd_to_dicom.py " +
                                     VOXLAB_SOURCE_DIR + "/datasets/headsq.nrrd " + out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Volume nrrd = loadVolume(std::string(VOXLAB_SOURCE_DIR) + "/datasets/headsq.nrrd");
    const Volume dicom = loadVolume(out);
    EXPECT_EQ(dicom.dims(), nrrd.dims());
    EXPECT_EQ(dicom.type(), nrrd.type());
    EXPECT_NEAR(glm::length(dicom.spacing() - nrrd.spacing()), 0.0, 1e-9);
    EXPECT_TRUE(dicom.bytes() == nrrd.bytes()) << "the voxels differ";
}

// ---- voxlab info ------------------------------------------------------------------------

TEST_F(Dicom, InfoPrintsTheSeries) {
    const std::string dir = series("info", "--description 'AX HEAD 2.5mm' --modality MR --no-rescale --spacing 2.5");
    const CommandResult r = runVoxlab("info " + dir + "/");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const std::string line : {"dataset:  info\n", "series:   AX HEAD 2.5mm\n", "modality: MR\n",
                                   "slices:   3 files, ordered by Image Position (Patient) along the normal, 2.5 mm",
                                   "orientation: axial", "rescale:  none", "spacing:  1 1 2.5\n"})
        EXPECT_NE(r.out.find(line), std::string::npos) << "expected '" << line << "' in:\n" << r.out;
}

// ---- errors --------------------------------------------------------------------------------

TEST_F(Dicom, FolderWithoutDicomFiles) {
    fs::create_directories(dir_ / "empty");
    expectError((dir_ / "empty").string(), {"no DICOM image files in this folder", "0 files"});
    fs::create_directories(dir_ / "text");
    std::ofstream(dir_ / "text" / "notes.txt") << "hello\n";
    expectError((dir_ / "text").string(), {"no DICOM image files", "1 not DICOM"});
    std::ofstream(dir_ / "junk.dcm") << std::string(300, 'x');
    expectError((dir_ / "junk.dcm").string(), {"not a DICOM file"});
}

TEST_F(Dicom, SeveralSeriesInAFolder) {
    expectError(series("two", "--second-series"),
                {"holds 2 series", "voxlab test series", "pass one file of the wanted series"});
}

TEST_F(Dicom, MixedSeries) {
    // The odd slice is named, whatever the files' order: the others are the reference.
    expectError(series("size", "--odd-size 1 --slices 4"),
                {"mixed series", "is 6x4 (Columns x Rows), not 5x4", "3 of 4 slices"});
    expectError(series("orient", "--odd-orientation 2"), {"mixed series", "(0020,0037) Image Orientation (Patient)"});
    expectError(series("bits", "--odd-bits 1 --base 0"), {"mixed series", "has 8 bits allocated, not 16"});
    expectError(series("sign", "--odd-signed 0 --base 0"),
                {"mixed series", "is unsigned, not signed", "(0028,0103) Pixel Representation"});
    expectError(series("same", "--shift 1 -1 --slices 4"), {"mixed series", "same position"});
}

TEST_F(Dicom, IncompleteOrUnevenSeries) {
    expectError(series("gap", "--slices 6 --drop 3 --spacing 2.5"),
                {"incomplete series", "gap of 5 mm", "2.5 mm apart", "1 missing slice"});
    expectError(series("gap4", "--slices 4 --drop 1"), {"incomplete series", "1 missing slice"});
    expectError(series("gaps", "--slices 9 --drop 3 --drop 4 --drop 5"), {"incomplete series", "3 missing slices"});
    expectError(series("uneven", "--slices 5 --shift 2 0.3"), {"uneven slice spacing", "1.3 mm"});
}

TEST_F(Dicom, TransferSyntaxesGdcmCannotDecode) {
    const std::string mpeg = series("mpeg2", "--transfer-syntax 1.2.840.10008.1.2.4.100");
    expectError(mpeg, {"cannot decode", "1.2.840.10008.1.2.4.100", "MPEG2"});
    expectError(mpeg + "/IM000.dcm", {"cannot decode", "1.2.840.10008.1.2.4.100"});
    const std::string madeUp = series("madeup", "--transfer-syntax 1.2.3.4.5.6.7.8");
    expectError(madeUp, {"transfer syntax '1.2.3.4.5.6.7.8' (unknown to GDCM)"});
    expectError(madeUp + "/IM001.dcm", {"transfer syntax '1.2.3.4.5.6.7.8'"});
}

TEST_F(Dicom, MissingRequiredTags) {
    const std::pair<const char*, const char*> cases[] = {
        {"Rows", "missing (0028,0010) Rows"},
        {"Columns", "missing (0028,0011) Columns"},
        {"PixelData", "missing (7FE0,0010) Pixel Data"},
        {"ImagePositionPatient", "missing (0020,0032) Image Position (Patient)"},
        {"ImageOrientationPatient", "missing (0020,0037) Image Orientation (Patient)"},
        {"PixelSpacing", "missing (0028,0030) Pixel Spacing"},
    };
    for (const auto& [keyword, phrase] : cases) {
        SCOPED_TRACE(keyword);
        expectError(series(keyword, std::string("--omit ") + keyword), {phrase});
    }
}

TEST_F(Dicom, OneSliceIsNotAVolume) {
    const std::string dir = series("one", "--slices 1");
    expectError(dir, {"only one slice", "at least 2"});
    expectError(dir + "/IM000.dcm", {"only one slice"});
}

// Checked before the voxels are allocated: the stored size against the cap,
// then the float32 the rescale needs.
TEST_F(Dicom, OverTheVolumeCap) {
    const std::string big = series("big", "--cols 400 --rows 400 --slices 4");  // 1.22 MiB of int16
    const std::string half = series("half", "--cols 300 --rows 300 --slices 4 --slope 0.5");  // 0.69 -> 1.37 MiB
    ::setenv(kVolumeCapVariable, "1", 1);
    expectError(big, {"400x400x4 uint16 is 1280000 bytes, over the 1 MiB volume cap"});
    expectError(half, {"300x300x4 float32", "over the 1 MiB volume cap"});
    ::unsetenv(kVolumeCapVariable);
    EXPECT_EQ(loadVolume(half).type(), VoxelType::Float32);
}

// Damaged files: one line each, never a crash.
TEST_F(Dicom, DamagedFiles) {
    const std::string dir = series("cut", "--cols 64 --rows 64 --order ascending");
    const fs::path file = fs::path(dir) / "IM001.dcm";
    fs::resize_file(file, fs::file_size(file) - 1000);
    expectError(dir, {"IM001.dcm: truncated (7FE0,0010) Pixel Data: 7192 bytes, expected 8192"});
    fs::resize_file(file, fs::file_size(file) - 7300);  // into the attributes
    expectError(dir, {"IM001.dcm"});

    // A Pixel Data length of 0xFFFFFFF0 in a file of 1 KiB: GDCM would
    // allocate and zero 4 GiB for it; the reader's memory cap stops it.
    const std::string vl = series("vl", "--order ascending");
    const fs::path im = fs::path(vl) / "IM001.dcm";
    std::string bytes = readFile(im.string());
    const std::size_t at = bytes.rfind(std::string("\xe0\x7f\x10\x00OW", 6));
    ASSERT_NE(at, std::string::npos);
    bytes.replace(at + 8, 4, "\xf0\xff\xff\xff");
    std::ofstream(im, std::ios::binary | std::ios::trunc) << bytes;
    const auto start = std::chrono::steady_clock::now();
    expectError(vl, {"IM001.dcm"});
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);

    const std::string magic = (dir_ / "magic").string();
    bytes = std::string(128, '\0');
    bytes += "DICM" + std::string(64, '\xff');
    std::ofstream(magic, std::ios::binary) << bytes;
    expectError(magic, {"not a DICOM file"});
}

// On the command line too: exactly one line on stderr, even when GDCM
// aborts (its assert message stays in the child).
TEST_F(Dicom, CommandLineErrorsAreOneLine) {
    const std::string mixed = series("mixed", "--odd-size 0");
    const std::string cut = series("cut", "--order ascending");
    fs::resize_file(fs::path(cut) / "IM001.dcm", 300);  // inside the attributes: GDCM asserts
    for (const auto& [dir, phrase] : {std::pair<std::string, std::string>{mixed, "mixed series"},
                                      {cut, "GDCM crashed reading IM001.dcm"}}) {
        const CommandResult r = runVoxlab("info " + dir);
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("voxlab: " + dir + ": ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(phrase), std::string::npos) << r.err;
    }
}

}  // namespace
}  // namespace voxlab::testing
