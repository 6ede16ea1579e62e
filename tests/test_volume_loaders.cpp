// Round trips through every volume format and voxel type (files written
// into a temporary folder by the test), plus the bundled datasets.
#include <gtest/gtest.h>

#include <stdlib.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "voxlab/error.h"
#include "voxlab/volume.h"

#include "support/datasets.h"
#include "support/temp_dir.h"

using namespace voxlab;
namespace fs = std::filesystem;

namespace {

// ---- helpers -----------------------------------------------------------------

using voxlab::testing::datasetPath;
using voxlab::testing::TempDir;

using Bytes = std::vector<std::uint8_t>;

void writeFile(const std::string& path, const std::string& text, const Bytes& data = {}) {
    fs::create_directories(fs::path(path).parent_path());
    std::ofstream out(path, std::ios::binary);
    out.write(text.data(), std::streamsize(text.size()));
    out.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size()));
    ASSERT_TRUE(out.good()) << path;
}

Bytes gzipped(const Bytes& data) {
    z_stream zs{};
    EXPECT_EQ(deflateInit2(&zs, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
    Bytes out(deflateBound(&zs, uLong(data.size())) + 64);
    zs.next_in = const_cast<Bytef*>(data.data());
    zs.avail_in = uInt(data.size());
    zs.next_out = out.data();
    zs.avail_out = uInt(out.size());
    EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
    out.resize(zs.total_out);
    deflateEnd(&zs);
    return out;
}

Bytes byteSwapped(Bytes bytes, std::size_t elem) {
    for (std::size_t i = 0; i + elem <= bytes.size(); i += elem)
        std::reverse(bytes.begin() + long(i), bytes.begin() + long(i + elem));
    return bytes;
}

Bytes concat(Bytes a, const Bytes& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// ---- sample volumes --------------------------------------------------------------

// A small non-cubic volume (so that axis order matters) with distinct
// values covering each type's range, including negatives and fractions.
const glm::ivec3 kDims(5, 3, 4);
const glm::dvec3 kSpacing(0.5, 1.25, 2.0);
const int kCount = 5 * 3 * 4;

struct Sample {
    VoxelType type;
    std::string nrrdType;  // a NRRD spelling of the type
    std::string datFormat; // a .dat spelling
    std::vector<double> values;
    Bytes bytes;           // little-endian
};

template <typename T>
Bytes pack(const std::vector<double>& values) {
    Bytes bytes(values.size() * sizeof(T));
    for (std::size_t i = 0; i < values.size(); ++i) {
        T v = static_cast<T>(values[i]);
        std::memcpy(bytes.data() + i * sizeof(T), &v, sizeof(T));
    }
    return bytes;
}

std::vector<Sample> samples() {
    std::vector<Sample> out;
    std::vector<double> u8, u16, i16, f32;
    for (int i = 0; i < kCount; ++i) {
        u8.push_back((i * 37 + 11) % 256);
        u16.push_back((i * 1103 + 7) % 65536);
        i16.push_back((i * 1103 + 7) % 65536 - 32768);
        f32.push_back(static_cast<float>((i - 30) * 0.37 + 1e-3 * i));
    }
    u8[3] = 255;
    u16[4] = 65535;
    i16[5] = -32768;
    out.push_back({VoxelType::UInt8, "unsigned char", "UCHAR", u8, pack<std::uint8_t>(u8)});
    out.push_back({VoxelType::UInt16, "uint16_t", "USHORT", u16, pack<std::uint16_t>(u16)});
    out.push_back({VoxelType::Int16, "signed short", "SHORT", i16, pack<std::int16_t>(i16)});
    out.push_back({VoxelType::Float32, "float", "FLOAT", f32, pack<float>(f32)});
    return out;
}

void expectVolume(const Volume& v, const Sample& s, glm::dvec3 spacing = kSpacing) {
    EXPECT_EQ(v.dims(), kDims);
    EXPECT_EQ(v.type(), s.type);
    EXPECT_EQ(v.spacing(), spacing);
    EXPECT_EQ(v.bytes(), s.bytes);
    for (int k = 0; k < kDims.z; ++k)
        for (int j = 0; j < kDims.y; ++j)
            for (int i = 0; i < kDims.x; ++i)
                ASSERT_EQ(v.value(i, j, k), s.values[std::size_t(i + 5 * (j + 3 * k))])
                    << "voxel " << i << "," << j << "," << k;
}

std::string nrrdHeader(const Sample& s, const std::string& extra) {
    return "NRRD0004\n# a test volume\ntype: " + s.nrrdType +
           "\ndimension: 3\nsizes: 5 3 4\nspacings: 0.5 1.25 2\n" + extra;
}

}  // namespace

// ---- NRRD -------------------------------------------------------------------------

TEST(NrrdLoader, AttachedRaw) {
    TempDir dir;
    for (const Sample& s : samples()) {
        SCOPED_TRACE(s.nrrdType);
        std::string path = dir.file("attached.nrrd");
        writeFile(path, nrrdHeader(s, "endian: little\nencoding: raw\n\n"), s.bytes);
        Volume v = loadNrrd(path);
        expectVolume(v, s);
        EXPECT_EQ(v.name(), "attached");
    }
}

TEST(NrrdLoader, AttachedGzip) {
    TempDir dir;
    for (const Sample& s : samples()) {
        for (const char* encoding : {"gzip", "gz"}) {
            SCOPED_TRACE(s.nrrdType + " " + encoding);
            std::string path = dir.file("gz.nrrd");
            writeFile(path, nrrdHeader(s, std::string("endian: little\nencoding: ") + encoding + "\n\n"),
                      gzipped(s.bytes));
            expectVolume(loadNrrd(path), s);
        }
    }
}

TEST(NrrdLoader, DetachedRaw) {
    TempDir dir;
    for (const Sample& s : samples()) {
        SCOPED_TRACE(s.nrrdType);
        // The header ends at end of file; the data lives in a subfolder.
        writeFile(dir.file("hdr/voxels/data.raw"), "", s.bytes);
        writeFile(dir.file("hdr/vol.nhdr"),
                  nrrdHeader(s, "endian: little\nencoding: raw\ndata file: voxels/data.raw\n"));
        Volume v = loadNrrd(dir.file("hdr/vol.nhdr"));
        expectVolume(v, s);
        EXPECT_EQ(v.name(), "vol");
    }
}

TEST(NrrdLoader, DetachedGzip) {
    TempDir dir;
    for (const Sample& s : samples()) {
        SCOPED_TRACE(s.nrrdType);
        writeFile(dir.file("data.raw.gz"), "", gzipped(s.bytes));
        writeFile(dir.file("vol.nhdr"),
                  nrrdHeader(s, "endian: little\nencoding: gzip\ndatafile: data.raw.gz\n\n"));
        expectVolume(loadNrrd(dir.file("vol.nhdr")), s);
    }
}

TEST(NrrdLoader, BigEndianIsSwapped) {
    TempDir dir;
    for (const Sample& s : samples()) {
        SCOPED_TRACE(s.nrrdType);
        Bytes big = byteSwapped(s.bytes, voxelTypeSize(s.type));
        writeFile(dir.file("big.nrrd"), nrrdHeader(s, "endian: big\nencoding: raw\n\n"), big);
        expectVolume(loadNrrd(dir.file("big.nrrd")), s);
        writeFile(dir.file("bigz.nrrd"), nrrdHeader(s, "endian: big\nencoding: gzip\n\n"), gzipped(big));
        expectVolume(loadNrrd(dir.file("bigz.nrrd")), s);
    }
}

TEST(NrrdLoader, ByteSkip) {
    TempDir dir;
    const Bytes junk = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17};
    for (const Sample& s : samples()) {
        SCOPED_TRACE(s.nrrdType);
        // Raw: skip bytes in the file after the header.
        writeFile(dir.file("skip.nrrd"), nrrdHeader(s, "endian: little\nencoding: raw\nbyte skip: 17\n\n"),
                  concat(junk, s.bytes));
        expectVolume(loadNrrd(dir.file("skip.nrrd")), s);
        // Detached raw: skip bytes at the start of the data file.
        writeFile(dir.file("skip.raw"), "", concat(junk, s.bytes));
        writeFile(dir.file("skip.nhdr"),
                  nrrdHeader(s, "endian: little\nencoding: raw\nbyte skip: 17\ndata file: skip.raw\n"));
        expectVolume(loadNrrd(dir.file("skip.nhdr")), s);
        // Gzip: the skip applies to the decompressed bytes (as in teem).
        writeFile(dir.file("skipz.nrrd"), nrrdHeader(s, "endian: little\nencoding: gzip\nbyteskip: 17\n\n"),
                  gzipped(concat(junk, s.bytes)));
        expectVolume(loadNrrd(dir.file("skipz.nrrd")), s);
    }
}

TEST(NrrdLoader, HeaderVariants) {
    TempDir dir;
    const Sample s = samples()[1];
    // Spacing from "space directions" when there is no "spacings" field.
    writeFile(dir.file("dirs.nrrd"),
              "NRRD0005\ntype: ushort\ndimension: 3\nspace: right-anterior-superior\n"
              "sizes: 5 3 4\nspace directions: (0.5,0,0) (0, 1.25, 0) (0,0,-2)\n"
              "kinds: domain domain domain\nspace origin: (1,2,3)\nendian: little\nencoding: raw\n\n",
              s.bytes);
    expectVolume(loadNrrd(dir.file("dirs.nrrd")), s);

    // "nan" spacing means 1; CRLF line endings; key:=value lines; comments.
    writeFile(dir.file("crlf.nrrd"),
              "NRRD0004\r\n# comment\r\ntype: ushort\r\ndimension: 3\r\nsizes: 5 3 4\r\n"
              "spacings: nan 1.25 NaN\r\nmodality:=CT\r\nendian: little\r\nencoding: raw\r\n\r\n",
              s.bytes);
    expectVolume(loadNrrd(dir.file("crlf.nrrd")), s, {1.0, 1.25, 1.0});

    // No spacing at all: 1 1 1.
    writeFile(dir.file("plain.nrrd"),
              "NRRD0001\ntype: ushort\ndimension: 3\nsizes: 5 3 4\nendian: little\nencoding: raw\n\n",
              s.bytes);
    expectVolume(loadNrrd(dir.file("plain.nrrd")), s, glm::dvec3(1.0));
}

TEST(NrrdLoader, TypeSpellings) {
    TempDir dir;
    const std::vector<std::pair<std::string, VoxelType>> spellings = {
        {"uchar", VoxelType::UInt8},          {"unsigned char", VoxelType::UInt8},
        {"uint8", VoxelType::UInt8},          {"uint8_t", VoxelType::UInt8},
        {"ushort", VoxelType::UInt16},        {"unsigned short", VoxelType::UInt16},
        {"uint16", VoxelType::UInt16},        {"uint16_t", VoxelType::UInt16},
        {"short", VoxelType::Int16},          {"int16", VoxelType::Int16},
        {"signed short", VoxelType::Int16},   {"int16_t", VoxelType::Int16},
        {"float", VoxelType::Float32}};
    for (const auto& [name, type] : spellings) {
        SCOPED_TRACE(name);
        writeFile(dir.file("t.nrrd"),
                  "NRRD0004\ntype: " + name + "\ndimension: 3\nsizes: 1 1 2\nencoding: raw\n\n",
                  Bytes(2 * voxelTypeSize(type), 0));
        EXPECT_EQ(loadNrrd(dir.file("t.nrrd")).type(), type);
    }
}

TEST(NrrdLoader, ConcatenatedGzipMembers) {
    TempDir dir;
    const Sample s = samples()[3];
    Bytes first(s.bytes.begin(), s.bytes.begin() + 100), second(s.bytes.begin() + 100, s.bytes.end());
    writeFile(dir.file("multi.nrrd"), nrrdHeader(s, "endian: little\nencoding: gzip\n\n"),
              concat(gzipped(first), gzipped(second)));
    expectVolume(loadNrrd(dir.file("multi.nrrd")), s);
}

TEST(NrrdLoader, SaveNrrdRoundTrip) {
    TempDir dir;
    for (const Sample& s : samples()) {
        for (bool gzip : {false, true}) {
            SCOPED_TRACE(s.nrrdType + (gzip ? " gzip" : " raw"));
            Volume original(kDims, s.type, {0.1, 1.0 / 3.0, 2.5}, s.bytes, "orig");
            saveNrrd(original, dir.file("saved.nrrd"), gzip);
            Volume back = loadVolume(dir.file("saved.nrrd"));
            expectVolume(back, s, {0.1, 1.0 / 3.0, 2.5});
            EXPECT_EQ(back.name(), "saved");
        }
    }
}

// ---- AVS field --------------------------------------------------------------------

TEST(FldLoader, Byte) {
    TempDir dir;
    const Sample s = samples()[0];
    writeFile(dir.file("b.fld"),
              "  # avs FIELD file (written by a test)\n# comment line\nndim=3\n"
              "dim1=5\ndim2=3\ndim3=4  # trailing comment\nnspace=3\nveclen=1\n"
              "data=byte\nfield=uniform\nlabel=density\nmin_ext=0 0 0\nmax_ext=4 2 3\n\f\f",
              s.bytes);
    Volume v = loadFld(dir.file("b.fld"));
    expectVolume(v, s, glm::dvec3(1.0));
    EXPECT_EQ(v.name(), "b");
}

TEST(FldLoader, ShortIsUnsigned) {
    TempDir dir;
    const Sample s = samples()[1];  // uint16 values up to 65535
    writeFile(dir.file("s.fld"),
              "# AVS field file\nndim = 3\ndim1 = 5\ndim2 = 3\ndim3 = 4\nveclen = 1\n"
              "data = short\nfield = uniform\n\f\f",
              s.bytes);
    Volume v = loadVolume(dir.file("s.fld"));
    expectVolume(v, s, glm::dvec3(1.0));
    EXPECT_EQ(v.maxValue(), 65535.0);
}

// ---- .dat / .raw ---------------------------------------------------------------

TEST(DatRawLoader, AllTypes) {
    TempDir dir;
    for (const Sample& s : samples()) {
        SCOPED_TRACE(s.datFormat);
        writeFile(dir.file("vol.raw"), "", s.bytes);
        writeFile(dir.file("vol.dat"),
                  "ObjectFileName: vol.raw\r\nTaggedFileName: ---\r\nResolution:     5 3 4\r\n"
                  "SliceThickness:\t0.5 1.25 2\r\nFormat: " + s.datFormat + "\r\nObjectModel: I\r\n"
                  "GridType: EQUIDISTANT\r\n");
        Volume v = loadVolume(dir.file("vol.dat"));
        expectVolume(v, s);
        EXPECT_EQ(v.name(), "vol");
    }
}

TEST(DatRawLoader, FormatSpellingsAndDefaults) {
    TempDir dir;
    const std::vector<std::pair<std::string, VoxelType>> formats = {
        {"UCHAR", VoxelType::UInt8},   {"uint8", VoxelType::UInt8},    {"BYTE", VoxelType::UInt8},
        {"USHORT", VoxelType::UInt16}, {"UINT16", VoxelType::UInt16},  {"SHORT", VoxelType::Int16},
        {"INT16", VoxelType::Int16},   {"FLOAT", VoxelType::Float32},  {"float32", VoxelType::Float32}};
    for (const auto& [name, type] : formats) {
        SCOPED_TRACE(name);
        writeFile(dir.file("sub/v.raw"), "", Bytes(2 * voxelTypeSize(type), 0));
        writeFile(dir.file("sub/v.dat"), "objectfilename: v.raw\nresolution: 2 1 1\nformat: " + name + "\n");
        Volume v = loadDatRaw(dir.file("sub/v.dat"));
        EXPECT_EQ(v.type(), type);
        EXPECT_EQ(v.spacing(), glm::dvec3(1.0));
    }
}

// ---- dispatch ------------------------------------------------------------------

TEST(LoadVolume, DispatchesByExtensionAndPrefix) {
    TempDir dir;
    const Sample s = samples()[0];
    writeFile(dir.file("UPPER.NRRD"), nrrdHeader(s, "encoding: raw\n\n"), s.bytes);
    Volume v = loadVolume(dir.file("UPPER.NRRD"));
    expectVolume(v, s);
    EXPECT_EQ(v.name(), "UPPER");

    Volume p = loadVolume("phantom:sphere:8");
    EXPECT_EQ(p.dims(), glm::ivec3(8));
    EXPECT_EQ(p.name(), "phantom:sphere:8");
}

// ---- bundled datasets ------------------------------------------------------------

struct Dataset {
    const char* file;
    glm::ivec3 dims;
    VoxelType type;
    glm::dvec3 spacing;
    double minValue, maxValue;  // measured with this loader
};

// Dims, type and spacing from datasets/PROVENANCE.md (via /work/shared).
const Dataset kDatasets[] = {
    {"bonsai.nrrd", {256, 256, 256}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"teapot.nrrd", {256, 256, 178}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"tooth.nrrd", {103, 94, 161}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"fuel.nrrd", {64, 64, 64}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"neghip.nrrd", {64, 64, 64}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"bucky.nrrd", {32, 32, 32}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"silicium.nrrd", {98, 34, 34}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"nucleon.nrrd", {41, 41, 41}, VoxelType::UInt8, {1, 1, 1}, 0, 249},
    {"cthead.nrrd", {256, 256, 113}, VoxelType::UInt16, {1, 1, 2}, 0, 3272},
    {"stent.nrrd", {128, 128, 256}, VoxelType::UInt16, {1, 1, 1}, 0, 2000},
    {"headsq.nrrd", {64, 64, 93}, VoxelType::Int16, {3.2, 3.2, 1.5}, 0, 3926},
    {"marschner_lobb.nrrd", {41, 41, 41}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"fld/tooth.fld", {103, 94, 161}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"fld/fuel.fld", {64, 64, 64}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"fld/bucky.fld", {32, 32, 32}, VoxelType::UInt8, {1, 1, 1}, 0, 255},
    {"tooth_labels.nrrd", {103, 94, 161}, VoxelType::UInt8, {1, 1, 1}, 0, 3},
    {"headsq_hu_labels.nrrd", {64, 64, 93}, VoxelType::UInt8, {3.2, 3.2, 1.5}, 0, 3},
    {"dicom/headsq_hu", {64, 64, 93}, VoxelType::Int16, {3.2, 3.2, 1.5}, -1024, 2902},
};

TEST(BundledDatasets, LoadWithDocumentedDimsTypeAndSpacing) {
    for (const Dataset& d : kDatasets) {
        SCOPED_TRACE(d.file);
        Volume v = loadVolume(datasetPath(d.file));
        EXPECT_EQ(v.dims(), d.dims);
        EXPECT_EQ(v.type(), d.type);
        EXPECT_EQ(v.spacing(), d.spacing);
        EXPECT_EQ(v.minValue(), d.minValue);
        EXPECT_EQ(v.maxValue(), d.maxValue);
        EXPECT_EQ(v.name(), fs::path(d.file).stem().string());
        EXPECT_EQ(v.histogram().total(), v.voxelCount());
    }
}

TEST(BundledDatasets, FldCopiesMatchTheNrrdFiles) {
    for (const char* name : {"bucky", "fuel", "tooth"}) {
        SCOPED_TRACE(name);
        Volume fld = loadVolume(datasetPath(std::string("fld/") + name + ".fld"));
        Volume nrrd = loadVolume(datasetPath(std::string(name) + ".nrrd"));
        EXPECT_EQ(fld.dims(), nrrd.dims());
        EXPECT_EQ(fld.type(), nrrd.type());
        EXPECT_TRUE(fld.bytes() == nrrd.bytes());
    }
}

// The bundled Marschner-Lobb file samples the signal at grid nodes,
// x = -1 + 2i/(N-1), quantised to 0..255 — an independent check of the
// loader's axis order and value decoding.
TEST(BundledDatasets, MarschnerLobbFileMatchesTheFormula) {
    Volume v = loadVolume(datasetPath("marschner_lobb.nrrd"));
    const int n = 41;
    const double pi = 3.14159265358979323846;
    double worst = 0.0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                double x = -1 + 2.0 * i / (n - 1), y = -1 + 2.0 * j / (n - 1), z = -1 + 2.0 * k / (n - 1);
                double r = std::sqrt(x * x + y * y);
                double rho = (1 - std::sin(pi * z / 2) + 0.25 * (1 + std::cos(2 * pi * 6 * std::cos(pi * r / 2)))) / 2.5;
                worst = std::max(worst, std::fabs(v.value(i, j, k) - 255.0 * rho));
            }
    EXPECT_LE(worst, 0.5 + 1e-6);
}
