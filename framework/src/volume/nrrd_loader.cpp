// voxlab: reading and writing NRRD files (http://teem.sourceforge.net/nrrd/format.html).
//
// A NRRD file starts with a magic line "NRRD000N" followed by text header
// lines "field: value" (comments start with '#', "key:=value" lines carry
// free-form metadata and are ignored). In an attached file (.nrrd) the
// header ends at the first blank line and the voxels follow; a detached
// header (.nhdr) names its data with "data file: NAME" (or "datafile:"),
// relative to the header's folder, and may simply end at end of file.
//
// What voxlab reads: dimension 3; type uchar/ushort/short/float under any of
// their NRRD spellings; encoding raw or gzip ("gz"); endian little or big;
// a non-negative "byte skip" (for gzip it applies to the decompressed
// bytes, as in teem); spacing from "spacings" ("nan" means 1; the sign is
// dropped) or else from the lengths of the "space directions" vectors.
// Other fields (kinds, space origin, ...) are tolerated and ignored.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include <zlib.h>

#include "volume_io_util.h"
#include "voxlab/atomic_file.h"
#include "voxlab/number_text.h"

namespace voxlab {

using namespace detail;

namespace {

struct NrrdHeader {
    std::map<std::string, std::string> fields;  // lower-case name -> value
    std::uint64_t dataOffset = 0;               // where attached data starts
};

std::string shorten(const std::string& line) {
    return line.size() > 60 ? line.substr(0, 57) + "..." : line;
}

// Splits the header into lines: the magic line first, then up to the first
// blank line (or end of file). Checks the magic, then that the header ends
// within kMaxHeaderBytes, then parses the fields.
NrrdHeader readHeader(const std::string& path) {
    std::uint64_t size = fileSize(path);
    if (size == 0) fail(path, "empty file");
    std::string text = readPrefix(path, kMaxHeaderBytes);
    const bool wholeFile = text.size() == size;

    std::vector<std::string> lines;
    std::size_t pos = 0;
    bool ended = false;
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        if (nl == std::string::npos && !wholeFile) break;  // line runs past the cap
        std::size_t end = nl == std::string::npos ? text.size() : nl;
        std::string line = text.substr(pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        pos = end + 1;
        if (line.empty() && !lines.empty()) {
            ended = true;
            break;
        }
        lines.push_back(line);
    }

    bool magicOk = !lines.empty() && lines[0].size() == 8 &&
                   lines[0].compare(0, 7, "NRRD000") == 0 && lines[0][7] >= '1' &&
                   lines[0][7] <= '9';
    if (!magicOk) fail(path, "not a NRRD file (first line must be the magic 'NRRD000N')");
    if (!ended && !wholeFile) {
        fail(path, "header does not end within " + std::to_string(kMaxHeaderBytes) + " bytes");
    }

    NrrdHeader header;
    header.dataOffset = ended ? pos : size;
    for (std::size_t i = 1; i < lines.size(); ++i) {
        const std::string& line = lines[i];
        if (line[0] == '#') continue;
        std::size_t field = line.find(": ");
        if (field == std::string::npos && line.back() == ':') field = line.size() - 1;
        std::size_t keyValue = line.find(":=");
        if (keyValue != std::string::npos && (field == std::string::npos || keyValue < field)) {
            continue;  // "key:=value" metadata
        }
        if (field == std::string::npos) fail(path, "malformed header line '" + shorten(line) + "'");
        std::string value = field + 2 <= line.size() ? line.substr(field + 2) : "";
        header.fields[toLower(trim(line.substr(0, field)))] = trim(value);
    }
    return header;
}

const std::string* find(const NrrdHeader& h, std::initializer_list<const char*> names) {
    for (const char* n : names) {
        auto it = h.fields.find(n);
        if (it != h.fields.end()) return &it->second;
    }
    return nullptr;
}

const std::string& require(const std::string& path, const NrrdHeader& h, const char* name) {
    const std::string* v = find(h, {name});
    if (!v) fail(path, std::string("missing '") + name + "' field");
    return *v;
}

VoxelType parseType(const std::string& path, const std::string& value) {
    std::string t = toLower(value);
    for (const char* s : {"uchar", "unsigned char", "uint8", "uint8_t"})
        if (t == s) return VoxelType::UInt8;
    for (const char* s : {"ushort", "unsigned short", "unsigned short int", "uint16", "uint16_t"})
        if (t == s) return VoxelType::UInt16;
    for (const char* s : {"short", "short int", "signed short", "signed short int", "int16", "int16_t"})
        if (t == s) return VoxelType::Int16;
    if (t == "float") return VoxelType::Float32;
    fail(path, "unsupported type '" + value + "' (supported: uchar, ushort, short, float)");
}

long long parseCount(const std::string& path, const char* what, const std::string& text) {
    long long v;
    if (!parseInt(text, v)) fail(path, std::string("invalid ") + what + " '" + text + "'");
    return v;
}

// One spacing from "spacings" or a "space directions" vector length.
double checkedSpacing(const std::string& path, const char* what, const std::string& text,
                      double value) {
    if (std::isnan(value)) return 1.0;
    value = std::fabs(value);
    if (!std::isfinite(value) || value == 0.0) {
        fail(path, std::string("invalid ") + what + " '" + text + "' (need finite, non-zero values)");
    }
    return value;
}

glm::dvec3 parseSpacing(const std::string& path, const NrrdHeader& h) {
    if (const std::string* s = find(h, {"spacings"})) {
        std::vector<std::string> words = splitWords(*s);
        if (words.size() != 3) fail(path, "spacings '" + *s + "' must have 3 values");
        glm::dvec3 spacing;
        for (int a = 0; a < 3; ++a) {
            double v;
            if (!parseDouble(words[a], v)) fail(path, "invalid spacings '" + *s + "'");
            spacing[a] = checkedSpacing(path, "spacings", *s, v);
        }
        return spacing;
    }
    if (const std::string* s = find(h, {"space directions"})) {
        // "(a,b,c) (d,e,f) (g,h,i)" or "none" for a non-spatial axis.
        std::vector<double> lengths;
        std::size_t i = 0;
        while (i < s->size()) {
            if (std::isspace(static_cast<unsigned char>((*s)[i]))) { ++i; continue; }
            if (s->compare(i, 4, "none") == 0) { lengths.push_back(1.0); i += 4; continue; }
            std::size_t close = s->find(')', i);
            if ((*s)[i] != '(' || close == std::string::npos) {
                fail(path, "invalid space directions '" + *s + "'");
            }
            std::string inner = s->substr(i + 1, close - i - 1);
            double sum = 0.0;
            std::size_t start = 0;
            while (start <= inner.size()) {
                std::size_t comma = std::min(inner.find(',', start), inner.size());
                double c;
                if (!parseDouble(trim(inner.substr(start, comma - start)), c)) {
                    fail(path, "invalid space directions '" + *s + "'");
                }
                sum += c * c;
                start = comma + 1;
            }
            lengths.push_back(checkedSpacing(path, "space directions", *s, std::sqrt(sum)));
            i = close + 1;
        }
        if (lengths.size() != 3) fail(path, "space directions '" + *s + "' must have 3 vectors");
        return {lengths[0], lengths[1], lengths[2]};
    }
    return glm::dvec3(1.0);
}

}  // namespace

Volume loadNrrd(const std::string& path) {
    NrrdHeader h = readHeader(path);

    VoxelType type = parseType(path, require(path, h, "type"));
    const std::string& dimText = require(path, h, "dimension");
    long long dimension = parseCount(path, "dimension", dimText);
    if (dimension != 3) fail(path, "dimension " + dimText + " is not supported (need 3)");

    const std::string& sizesText = require(path, h, "sizes");
    std::vector<std::string> sizes = splitWords(sizesText);
    if (sizes.size() != 3) {
        fail(path, "sizes '" + sizesText + "' must have 3 values (dimension is 3)");
    }
    long long n[3];
    for (int a = 0; a < 3; ++a) {
        if (!parseInt(sizes[a], n[a])) fail(path, "invalid sizes '" + sizesText + "'");
    }
    // Checked against kMaxVoxels before anything is read; over the memory
    // cap the voxels are streamed from the file (voxel_store.cpp).
    const std::uint64_t expected = checkedVoxelCount(path, "sizes", n[0], n[1], n[2]) * voxelTypeSize(type);
    glm::dvec3 spacing = parseSpacing(path, h);

    const std::string& encodingText = require(path, h, "encoding");
    std::string encoding = toLower(encodingText);
    bool gzip = encoding == "gzip" || encoding == "gz";
    if (!gzip && encoding != "raw") {
        fail(path, "unknown encoding '" + encodingText + "' (supported: raw, gzip)");
    }

    bool bigEndian = false;
    if (const std::string* e = find(h, {"endian"})) {
        std::string v = toLower(*e);
        if (v != "little" && v != "big") fail(path, "unknown endian '" + *e + "' (expected little or big)");
        bigEndian = v == "big";
    }

    long long skip = 0;
    if (const std::string* s = find(h, {"byte skip", "byteskip"})) {
        skip = parseCount(path, "byte skip", *s);
        if (skip < 0) fail(path, "byte skip " + *s + " is not supported (need >= 0)");
    }
    if (const std::string* s = find(h, {"line skip", "lineskip"})) {
        if (parseCount(path, "line skip", *s) != 0) fail(path, "line skip " + *s + " is not supported");
    }

    std::string dataPath = path;
    std::uint64_t offset = h.dataOffset;
    if (const std::string* f = find(h, {"data file", "datafile"})) {
        bool multi = *f == "LIST" || (splitWords(*f).size() >= 4 && f->find('%') != std::string::npos);
        if (multi) fail(path, "multi-file data ('" + *f + "') is not supported");
        dataPath = siblingPath(path, *f);
        std::error_code ec;
        if (!std::filesystem::is_regular_file(dataPath, ec)) {
            fail(path, "data file '" + *f + "' not found");
        }
        offset = 0;
    }

    const std::size_t elem = voxelTypeSize(type);
    const glm::ivec3 dims = glm::ivec3(int(n[0]), int(n[1]), int(n[2]));
    const bool swap = bigEndian == hostIsLittleEndian();
    if (overMemoryCap(expected)) {
        if (!gzip && !swap) return buildVolume(path, dims, type, spacing, mapRawVoxels(path, dataPath, offset + std::uint64_t(skip), expected));
        return buildVolume(path, dims, type, spacing,
                           streamThroughCache(path, dataPath, offset, std::uint64_t(skip), expected, gzip, swap ? elem : 0));
    }
    std::vector<std::uint8_t> bytes =
        gzip ? inflateGzipFile(path, dataPath, offset, std::uint64_t(skip), expected)
             : readRawVoxels(path, dataPath, offset + std::uint64_t(skip), expected);
    if (swap) swapByteOrder(bytes, elem);
    return buildVolume(path, dims, type, spacing, std::move(bytes));
}

// ---- writing -----------------------------------------------------------------

namespace {

const char* nrrdTypeName(VoxelType type) {
    switch (type) {
        case VoxelType::UInt8: return "uchar";
        case VoxelType::UInt16: return "ushort";
        case VoxelType::Int16: return "short";
        case VoxelType::Float32: return "float";
    }
    return "?";
}

// Shortest text that reads back as exactly the same double.
std::string exactText(double v) {
    return shortestText(v);
}

// The gzip encoding of `data`, appended to `out` chunk by chunk.
void appendGzip(std::string& out, const std::string& path, const ByteView& data) {
    z_stream zs{};
    if (deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        fail(path, "cannot initialise zlib");
    }
    struct Guard { z_stream* zs; ~Guard() { deflateEnd(zs); } } guard{&zs};
    std::vector<std::uint8_t> chunk(1 << 18);
    std::size_t fed = 0;
    int ret = Z_OK;
    while (ret != Z_STREAM_END) {
        if (zs.avail_in == 0 && fed < data.size()) {
            zs.next_in = const_cast<Bytef*>(data.data() + fed);
            zs.avail_in = static_cast<uInt>(std::min<std::size_t>(data.size() - fed, 1u << 30));
            fed += zs.avail_in;
        }
        zs.next_out = chunk.data();
        zs.avail_out = static_cast<uInt>(chunk.size());
        ret = deflate(&zs, fed == data.size() && zs.avail_in == 0 ? Z_FINISH : Z_NO_FLUSH);
        if (ret == Z_STREAM_ERROR) fail(path, "gzip compression failed");
        out.append(reinterpret_cast<const char*>(chunk.data()), chunk.size() - zs.avail_out);
    }
}

std::string nrrdHeader(const Volume& volume, bool gzip) {
    const glm::ivec3 d = volume.dims();
    const glm::dvec3 s = volume.spacing();
    std::string h = "NRRD0004\n# written by voxlab\ntype: " + std::string(nrrdTypeName(volume.type())) +
                    "\ndimension: 3\nsizes: " + std::to_string(d.x) + " " + std::to_string(d.y) + " " +
                    std::to_string(d.z) + "\nspacings: " + exactText(s.x) + " " + exactText(s.y) + " " +
                    exactText(s.z) + "\n";
    if (voxelTypeSize(volume.type()) > 1) h += std::string("endian: ") + (hostIsLittleEndian() ? "little" : "big") + "\n";
    return h + "encoding: " + (gzip ? "gzip" : "raw") + "\n\n";
}

}  // namespace

// The whole file is put together in memory and saved by writeFileAtomically,
// so that a failed save (a full disk, a missing folder) leaves the old file
// as it was and says so. That costs a second copy of the voxels while it
// runs (less for gzip); saveNrrd is for tests and tools, not for the loaders.
void saveNrrd(const Volume& volume, const std::string& path, bool gzip) {
    if (volume.voxelCount() == 0) fail(path, "cannot save an empty volume");
    std::string file = nrrdHeader(volume, gzip);
    if (gzip) {
        appendGzip(file, path, volume.bytes());
    } else {
        file.reserve(file.size() + volume.bytes().size());
        file.append(reinterpret_cast<const char*>(volume.bytes().data()), volume.bytes().size());
    }
    writeFileAtomically(path, file);
}

}  // namespace voxlab
