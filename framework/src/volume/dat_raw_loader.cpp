// voxlab: reading volvis.org / QVis style ".dat" descriptions of ".raw" files.
//
//   ObjectFileName: bonsai.raw      <- the voxels, relative to the .dat's folder
//   Resolution:     256 256 256     <- x y z
//   SliceThickness: 1 1 1           <- spacing (optional, default 1 1 1)
//   Format:         UCHAR           <- UCHAR/UINT8/BYTE, USHORT/UINT16,
//                                      SHORT/INT16, FLOAT/FLOAT32
//
// Keys are case-insensitive, "key: value" one per line; other keys
// (TaggedFileName, GridType, ...) are tolerated. ObjectModel, when given,
// must be "I" (one scalar per voxel). The .raw file holds exactly the
// voxels, x fastest, multi-byte values little-endian.
#include <cmath>
#include <filesystem>
#include <map>

#include "volume_io_util.h"

namespace voxlab {

using namespace detail;

namespace {

VoxelType parseFormat(const std::string& path, const std::string& value) {
    std::string f = toLower(value);
    if (f == "uchar" || f == "uint8" || f == "byte") return VoxelType::UInt8;
    if (f == "ushort" || f == "uint16") return VoxelType::UInt16;
    if (f == "short" || f == "int16") return VoxelType::Int16;
    if (f == "float" || f == "float32") return VoxelType::Float32;
    fail(path, "unsupported format '" + value + "' (supported: UCHAR, USHORT, SHORT, FLOAT)");
}

}  // namespace

Volume loadDatRaw(const std::string& path) {
    std::uint64_t size = fileSize(path);
    if (size == 0) fail(path, "empty file");
    if (size > kMaxHeaderBytes) {
        fail(path, "too large for a .dat description (more than " +
                       std::to_string(kMaxHeaderBytes) + " bytes)");
    }
    std::string text = readPrefix(path, kMaxHeaderBytes);

    std::map<std::string, std::string> fields;  // lower-case key -> value
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t nl = std::min(text.find('\n', pos), text.size());
        std::string line = trim(text.substr(pos, nl - pos));
        pos = nl + 1;
        if (line.empty() || line[0] == '#') continue;
        std::size_t colon = line.find(':');
        if (colon == std::string::npos) {
            fail(path, "malformed line '" + line.substr(0, 60) + "' (expected 'Key: value')");
        }
        fields[toLower(trim(line.substr(0, colon)))] = trim(line.substr(colon + 1));
    }
    auto require = [&](const char* key, const char* shown) -> const std::string& {
        auto it = fields.find(key);
        if (it == fields.end()) fail(path, std::string("missing '") + shown + "'");
        return it->second;
    };

    const std::string& object = require("objectfilename", "ObjectFileName");
    const std::string& resolution = require("resolution", "Resolution");
    VoxelType type = parseFormat(path, require("format", "Format"));

    std::vector<std::string> words = splitWords(resolution);
    long long n[3];
    if (words.size() != 3 || !parseInt(words[0], n[0]) || !parseInt(words[1], n[1]) ||
        !parseInt(words[2], n[2])) {
        fail(path, "invalid Resolution '" + resolution + "' (need 3 integers)");
    }
    // Checked against kMaxVoxels before anything is read; over the memory
    // cap the voxels are streamed from the .raw file (voxel_store.cpp).
    const std::uint64_t expected = checkedVoxelCount(path, "Resolution", n[0], n[1], n[2]) * voxelTypeSize(type);

    glm::dvec3 spacing(1.0);
    if (auto it = fields.find("slicethickness"); it != fields.end()) {
        std::vector<std::string> s = splitWords(it->second);
        bool ok = s.size() == 3;
        for (int a = 0; ok && a < 3; ++a) {
            ok = parseDouble(s[a], spacing[a]) && std::isfinite(spacing[a]) && spacing[a] > 0.0;
        }
        if (!ok) fail(path, "invalid SliceThickness '" + it->second + "' (need 3 positive numbers)");
    }
    if (auto it = fields.find("objectmodel"); it != fields.end() && toLower(it->second) != "i") {
        fail(path, "ObjectModel '" + it->second + "' is not supported (need I)");
    }

    std::string rawPath = siblingPath(path, object);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(rawPath, ec)) {
        fail(path, "data file '" + object + "' not found");
    }
    std::size_t elem = voxelTypeSize(type);
    const glm::ivec3 dims = glm::ivec3(int(n[0]), int(n[1]), int(n[2]));
    if (overMemoryCap(expected))
        return buildVolume(path, dims, type, spacing,
                           hostIsLittleEndian() ? mapRawVoxels(path, rawPath, 0, expected)
                                                : streamThroughCache(path, rawPath, 0, 0, expected, false, elem));
    std::vector<std::uint8_t> bytes = readRawVoxels(path, rawPath, 0, expected);
    if (!hostIsLittleEndian()) swapByteOrder(bytes, elem);
    return buildVolume(path, dims, type, spacing, std::move(bytes));
}

}  // namespace voxlab
