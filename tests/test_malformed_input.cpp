// Malformed volume files: every case must throw a voxlab::Error with a
// one-line message "<path>: <problem>" containing a specific phrase — never
// crash, hang or allocate according to absurd header sizes.
#include <gtest/gtest.h>

#include <stdlib.h>
#include <zlib.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "voxlab/error.h"
#include "voxlab/volume.h"

#include "support/temp_dir.h"

using namespace voxlab;
namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

namespace {

class MalformedInput : public ::testing::Test {
protected:
    // Writes `text` then `data` to a file in the temporary folder.
    std::string write(const std::string& name, const std::string& text, const Bytes& data = {}) {
        return tmp_.write(name, text, data);
    }

    // loadVolume(path) must throw "<path>: ...<phrase>..." on one line,
    // within `maxSeconds`.
    void expectFailure(const std::string& path, const std::string& phrase, double maxSeconds = 5.0) {
        auto start = std::chrono::steady_clock::now();
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
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::cout << "    message: " << message << "\n";
        EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
        EXPECT_NE(message.find(phrase), std::string::npos) << "expected '" << phrase << "' in: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_LT(seconds, maxSeconds) << message;
    }

    voxlab::testing::TempDir tmp_{"voxlab-malformed"};
    const fs::path dir_ = tmp_.path();
};

Bytes gzipped(const Bytes& data) {
    Bytes out(compressBound(uLong(data.size())) + 64);
    z_stream zs{};
    deflateInit2(&zs, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
    zs.next_in = const_cast<Bytef*>(data.data());
    zs.avail_in = uInt(data.size());
    zs.next_out = out.data();
    zs.avail_out = uInt(out.size());
    deflate(&zs, Z_FINISH);
    out.resize(zs.total_out);
    deflateEnd(&zs);
    return out;
}

// Pseudo-random bytes: compress badly, so corruption is noticed mid-stream.
Bytes noise(std::size_t n) {
    Bytes b(n);
    std::uint32_t state = 12345;
    for (auto& v : b) {
        state = state * 1664525u + 1013904223u;
        v = std::uint8_t(state >> 24);
    }
    return b;
}

std::string nrrd(const std::string& fields) { return "NRRD0004\n" + fields + "\n"; }
const std::string kGood = "type: uchar\ndimension: 3\nsizes: 4 4 4\n";

}  // namespace

// ---- NRRD: data size --------------------------------------------------------------

TEST_F(MalformedInput, NrrdTruncatedRawData) {
    expectFailure(write("short.nrrd", nrrd("type: ushort\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n"), Bytes(100)),
                  "truncated data: expected 128 bytes, got 100");
}

TEST_F(MalformedInput, NrrdRawDataTooLong) {
    expectFailure(write("long.nrrd", nrrd(kGood + "encoding: raw\n"), Bytes(65)),
                  "data is too long: expected 64 bytes, got 65");
}

TEST_F(MalformedInput, NrrdTruncatedGzipStream) {
    Bytes z = gzipped(noise(64));
    z.resize(z.size() / 2);
    expectFailure(write("cut.nrrd", nrrd(kGood + "encoding: gzip\n"), z), "truncated data: expected 64 bytes");
}

TEST_F(MalformedInput, NrrdGzipDataTooShort) {
    expectFailure(write("few.nrrd", nrrd(kGood + "encoding: gzip\n"), gzipped(noise(40))),
                  "truncated data: expected 64 bytes, got 40");
}

TEST_F(MalformedInput, NrrdGzipDataTooLong) {
    expectFailure(write("many.nrrd", nrrd(kGood + "encoding: gzip\n"), gzipped(noise(80))),
                  "gzip data is too long: more than 64 bytes");
}

TEST_F(MalformedInput, NrrdCorruptGzipHeader) {
    expectFailure(write("notgz.nrrd", nrrd(kGood + "encoding: gzip\n"), noise(200)), "corrupt gzip data (");
}

TEST_F(MalformedInput, NrrdCorruptGzipStream) {
    Bytes z = gzipped(noise(4096));
    for (std::size_t i = 40; i < 60; ++i) z[i] ^= 0x5a;  // damage the deflate data
    expectFailure(write("damaged.nrrd",
                        nrrd("type: uchar\ndimension: 3\nsizes: 16 16 16\nencoding: gzip\n"), z),
                  "corrupt gzip data (");
}

TEST_F(MalformedInput, NrrdEmptyAttachedData) {
    expectFailure(write("nodata.nrrd", nrrd(kGood + "encoding: raw\n")), "truncated data: expected 64 bytes, got 0");
}

// ---- NRRD: absurd sizes (must fail before allocating) ---------------------------

TEST_F(MalformedInput, NrrdAbsurdSizes) {
    expectFailure(write("huge.nrrd", nrrd("type: uchar\ndimension: 3\nsizes: 100000 100000 100000\nencoding: raw\n"),
                        Bytes(10)),
                  "sizes 100000 100000 100000 exceed the limit of 17592186044416 voxels", 1.0);
    expectFailure(write("hugez.nrrd", nrrd("type: float\ndimension: 3\nsizes: 100000 100000 100000\nencoding: gzip\n"),
                        gzipped(Bytes(10))),
                  "exceed the limit of 17592186044416 voxels", 1.0);
    expectFailure(write("overflow.nrrd",
                        nrrd("type: uchar\ndimension: 3\nsizes: 4294967296 4294967296 4294967296\nencoding: raw\n")),
                  "exceed the limit", 1.0);
}

TEST_F(MalformedInput, NrrdLargestSizeWithTinyDataFailsFast) {
    // 2^31 voxels is allowed, but the data is not there: no 2 GiB allocation.
    expectFailure(write("big.nrrd", nrrd("type: uchar\ndimension: 3\nsizes: 1024 1024 2048\nencoding: raw\n"), Bytes(10)),
                  "truncated data: expected 2147483648 bytes, got 10", 1.0);
    expectFailure(write("bigz.nrrd", nrrd("type: uchar\ndimension: 3\nsizes: 1024 1024 2048\nencoding: gzip\n"),
                        gzipped(Bytes(1000))),
                  "truncated data: expected 2147483648 bytes, got 1000", 1.0);
}

// ---- NRRD: header fields ------------------------------------------------------------

TEST_F(MalformedInput, NrrdUnknownType) {
    expectFailure(write("double.nrrd", nrrd("type: double\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n"), Bytes(8)),
                  "unsupported type 'double' (supported: uchar, ushort, short, float)");
    expectFailure(write("int8.nrrd", nrrd("type: signed char\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n"), Bytes(1)),
                  "unsupported type 'signed char'");
    expectFailure(write("junk.nrrd", nrrd("type: banana\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n"), Bytes(1)),
                  "unsupported type 'banana'");
}

TEST_F(MalformedInput, NrrdUnknownEncoding) {
    expectFailure(write("bz.nrrd", nrrd(kGood + "encoding: bzip2\n"), Bytes(64)),
                  "unknown encoding 'bzip2' (supported: raw, gzip)");
}

TEST_F(MalformedInput, NrrdMissingDetachedDataFile) {
    expectFailure(write("x.nhdr", nrrd(kGood + "encoding: raw\ndata file: x.raw\n")), "data file 'x.raw' not found");
}

TEST_F(MalformedInput, NrrdTruncatedDetachedData) {
    write("d.raw", "", Bytes(10));
    expectFailure(write("d.nhdr", nrrd(kGood + "encoding: raw\ndata file: d.raw\n")),
                  "truncated data in '");
}

TEST_F(MalformedInput, NrrdHeaderNeverEnds) {
    std::string lines;
    while (lines.size() < (1 << 20)) lines += "# a comment line that goes on and on\n";
    expectFailure(write("endless.nrrd", "NRRD0004\n" + kGood + lines), "header does not end within 65536 bytes");
    std::string oneLine(1 << 20, 'a');
    expectFailure(write("longline.nrrd", "NRRD0004\ntype: " + oneLine), "header does not end within 65536 bytes");
}

TEST_F(MalformedInput, NrrdWrongMagic) {
    expectFailure(write("magic.nrrd", "NRRX0004\n" + kGood + "encoding: raw\n\n", Bytes(64)), "not a NRRD file");
    expectFailure(write("binary.nrrd", "", noise(5000)), "not a NRRD file");
}

TEST_F(MalformedInput, NrrdDimensionNot3) {
    expectFailure(write("dim2.nrrd", nrrd("type: uchar\ndimension: 2\nsizes: 4 4\nencoding: raw\n"), Bytes(16)),
                  "dimension 2 is not supported (need 3)");
    expectFailure(write("dim4.nrrd", nrrd("type: uchar\ndimension: 4\nsizes: 1 4 4 4\nencoding: raw\n"), Bytes(64)),
                  "dimension 4 is not supported (need 3)");
}

TEST_F(MalformedInput, NrrdNonPositiveSizes) {
    expectFailure(write("neg.nrrd", nrrd("type: uchar\ndimension: 3\nsizes: 4 -4 4\nencoding: raw\n"), Bytes(64)),
                  "sizes must be positive, got 4 -4 4");
    expectFailure(write("zero.nrrd", nrrd("type: uchar\ndimension: 3\nsizes: 0 4 4\nencoding: raw\n")),
                  "sizes must be positive, got 0 4 4");
}

TEST_F(MalformedInput, NrrdNonNumericSizes) {
    expectFailure(write("nan.nrrd", nrrd("type: uchar\ndimension: 3\nsizes: 4 four 4\nencoding: raw\n"), Bytes(64)),
                  "invalid sizes '4 four 4'");
    expectFailure(write("frac.nrrd", nrrd("type: uchar\ndimension: 3\nsizes: 4 4.5 4\nencoding: raw\n"), Bytes(64)),
                  "invalid sizes");
    expectFailure(write("count.nrrd", nrrd("type: uchar\ndimension: 3\nsizes: 4 4\nencoding: raw\n"), Bytes(16)),
                  "must have 3 values");
}

TEST_F(MalformedInput, NrrdOtherBadFields) {
    expectFailure(write("notype.nrrd", nrrd("dimension: 3\nsizes: 4 4 4\nencoding: raw\n"), Bytes(64)),
                  "missing 'type' field");
    expectFailure(write("endian.nrrd", nrrd(kGood + "endian: middle\nencoding: raw\n"), Bytes(64)),
                  "unknown endian 'middle'");
    expectFailure(write("skip.nrrd", nrrd(kGood + "byte skip: -1\nencoding: raw\n"), Bytes(64)),
                  "byte skip -1 is not supported");
    expectFailure(write("spacing.nrrd", nrrd(kGood + "spacings: 1 0 1\nencoding: raw\n"), Bytes(64)),
                  "invalid spacings '1 0 1'");
    expectFailure(write("garbage.nrrd", nrrd(kGood + "this is not a field\nencoding: raw\n"), Bytes(64)),
                  "malformed header line 'this is not a field'");
}

TEST_F(MalformedInput, NrrdNaNVoxels) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Bytes data(8 * sizeof(float), 0);
    std::memcpy(data.data() + 5 * sizeof(float), &nan, sizeof(float));  // voxel (1,0,1)
    expectFailure(write("nanvox.nrrd", nrrd("type: float\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n"), data),
                  "float32 voxel (1, 0, 1) is NaN");
}

// ---- AVS field -------------------------------------------------------------------

const std::string kFld = "# AVS field file\nndim=3\ndim1=4\ndim2=4\ndim3=4\nnspace=3\n";

TEST_F(MalformedInput, FldVeclen2) {
    expectFailure(write("vec.fld", kFld + "veclen=2\ndata=byte\nfield=uniform\n\f\f", Bytes(128)),
                  "veclen 2 is not supported (need 1)");
}

TEST_F(MalformedInput, FldNdim2) {
    expectFailure(write("flat.fld", "# AVS field file\nndim=2\ndim1=4\ndim2=4\nveclen=1\ndata=byte\n\f\f", Bytes(16)),
                  "ndim 2 is not supported (need 3)");
}

TEST_F(MalformedInput, FldUnsupportedData) {
    expectFailure(write("float.fld", kFld + "veclen=1\ndata=float\nfield=uniform\n\f\f", Bytes(256)),
                  "unsupported data type 'float' (supported: byte, short)");
    expectFailure(write("rect.fld", kFld + "veclen=1\ndata=byte\nfield=rectilinear\n\f\f", Bytes(64)),
                  "field 'rectilinear' is not supported (need uniform)");
}

TEST_F(MalformedInput, FldDataSize) {
    expectFailure(write("short.fld", kFld + "veclen=1\ndata=short\n\f\f", Bytes(100)),
                  "truncated data: expected 128 bytes, got 100");
    expectFailure(write("long.fld", kFld + "veclen=1\ndata=byte\n\f\f", Bytes(70)),
                  "data is too long: expected 64 bytes, got 70");
    expectFailure(write("huge.fld", "# AVS field file\nndim=3\ndim1=100000\ndim2=100000\ndim3=100000\ndata=byte\n\f\f"),
                  "dims 100000 100000 100000 exceed the limit of 17592186044416 voxels", 1.0);
    expectFailure(write("zero.fld", "# AVS field file\nndim=3\ndim1=0\ndim2=4\ndim3=4\ndata=byte\n\f\f"),
                  "dims must be positive");
    expectFailure(write("abc.fld", "# AVS field file\nndim=3\ndim1=abc\ndim2=4\ndim3=4\ndata=byte\n\f\f"),
                  "invalid dim1 'abc'");
}

TEST_F(MalformedInput, FldHeaderNeverEnds) {
    std::string lines;
    while (lines.size() < (1 << 20)) lines += "label=something\n";
    expectFailure(write("endless.fld", kFld + lines), "header does not end within 65536 bytes");
    expectFailure(write("noff.fld", kFld + "veclen=1\ndata=byte\n", Bytes(64)),
                  "header does not end: no form-feed pair (0x0C 0x0C)");
}

TEST_F(MalformedInput, FldWrongMagic) {
    expectFailure(write("magic.fld", "# not an AVS file\nndim=3\n\f\f"), "not an AVS field file");
}

// ---- .dat / .raw ------------------------------------------------------------------

TEST_F(MalformedInput, DatMissingRaw) {
    expectFailure(write("v.dat", "ObjectFileName: missing.raw\nResolution: 4 4 4\nFormat: UCHAR\n"),
                  "data file 'missing.raw' not found");
}

TEST_F(MalformedInput, DatBadFields) {
    write("v.raw", "", Bytes(64));
    expectFailure(write("fmt.dat", "ObjectFileName: v.raw\nResolution: 4 4 4\nFormat: DOUBLE\n"),
                  "unsupported format 'DOUBLE'");
    expectFailure(write("res.dat", "ObjectFileName: v.raw\nResolution: 4 4\nFormat: UCHAR\n"),
                  "invalid Resolution '4 4'");
    expectFailure(write("nores.dat", "ObjectFileName: v.raw\nFormat: UCHAR\n"), "missing 'Resolution'");
    expectFailure(write("thick.dat", "ObjectFileName: v.raw\nResolution: 4 4 4\nSliceThickness: 1 -1 1\nFormat: UCHAR\n"),
                  "invalid SliceThickness");
    expectFailure(write("rgba.dat", "ObjectFileName: v.raw\nResolution: 4 4 4\nFormat: UCHAR\nObjectModel: RGBA\n"),
                  "ObjectModel 'RGBA' is not supported");
    expectFailure(write("trunc.dat", "ObjectFileName: v.raw\nResolution: 4 4 4\nFormat: USHORT\n"),
                  "truncated data in '");
    expectFailure(write("huge.dat", "ObjectFileName: v.raw\nResolution: 100000 100000 100000\nFormat: UCHAR\n"),
                  "Resolution 100000 100000 100000 exceed the limit", 1.0);
    expectFailure(write("big.dat", std::string(100000, '#')), "too large for a .dat description");
}

// ---- any format -------------------------------------------------------------------

TEST_F(MalformedInput, EmptyFiles) {
    expectFailure(write("empty.nrrd", ""), "empty file");
    expectFailure(write("empty.nhdr", ""), "empty file");
    expectFailure(write("empty.fld", ""), "empty file");
    expectFailure(write("empty.dat", ""), "empty file");
}

TEST_F(MalformedInput, UnknownExtension) {
    expectFailure(write("volume.xyz", "hello"), "unknown volume format '.xyz'");
    expectFailure(write("noext", "hello"), "no file extension");
}

TEST_F(MalformedInput, NonexistentFile) {
    expectFailure((dir_ / "nope.nrrd").string(), "no such file");
    expectFailure((dir_ / "nope.xyz").string(), "no such file");
    fs::create_directory(dir_ / "folder.nrrd");
    expectFailure((dir_ / "folder.nrrd").string(), "is a directory");
}
