// voxlab: reading AVS field files (.fld), as used by classic course skeletons.
//
//   # AVS field file          <- first line ('#', then "AVS field file", any case)
//   ndim=3                    <- key=value lines; '#' starts a comment
//   dim1=256  dim2=256  dim3=113   (one per line)
//   nspace=3
//   veclen=1                  <- must be 1 (scalar data)
//   data=short                <- byte (uint8) or short (16-bit little-endian,
//   field=uniform                read as unsigned uint16, like the skeletons do)
//   <0x0C><0x0C>              <- two form-feed bytes end the header
//   raw voxels, x fastest, exactly dim1*dim2*dim3 of them
//
// AVS fields carry no spacing: voxlab uses 1 1 1. min_ext/max_ext, label,
// unit, "variable N file=..." and other lines are tolerated and ignored.
#include <map>

#include "volume_io_util.h"

namespace voxlab {

using namespace detail;

namespace {

bool isMagicLine(std::string line) {
    line = trim(line);
    if (line.empty() || line[0] != '#') return false;
    return toLower(trim(line.substr(1))).rfind("avs field file", 0) == 0;
}

long long intField(const std::string& path, const std::map<std::string, std::string>& fields,
                   const std::string& key, long long fallback, bool required) {
    auto it = fields.find(key);
    if (it == fields.end()) {
        if (required) fail(path, "missing '" + key + "' field");
        return fallback;
    }
    long long v;
    if (!parseInt(it->second, v)) fail(path, "invalid " + key + " '" + it->second + "'");
    return v;
}

}  // namespace

Volume loadFld(const std::string& path) {
    std::uint64_t size = fileSize(path);
    if (size == 0) fail(path, "empty file");
    std::string text = readPrefix(path, kMaxHeaderBytes);

    std::string firstLine = text.substr(0, text.find_first_of("\n\f"));
    if (!isMagicLine(firstLine)) {
        fail(path, "not an AVS field file (first line must be '# AVS field file')");
    }
    std::size_t headerEnd = text.find("\f\f");
    if (headerEnd == std::string::npos) {
        if (text.size() < size) {
            fail(path, "header does not end within " + std::to_string(kMaxHeaderBytes) + " bytes");
        }
        fail(path, "header does not end: no form-feed pair (0x0C 0x0C) before end of file");
    }

    std::map<std::string, std::string> fields;
    std::size_t pos = 0;  // the magic line is a comment like any other
    while (pos < headerEnd) {
        std::size_t nl = std::min(text.find('\n', pos), headerEnd);
        std::string line = text.substr(pos, nl - pos);
        pos = nl + 1;
        line = trim(line.substr(0, line.find('#')));
        if (line.empty()) continue;
        std::string lower = toLower(line);
        if (lower.rfind("variable", 0) == 0 || lower.rfind("coord", 0) == 0) continue;
        std::size_t eq = line.find('=');
        if (eq == std::string::npos) {
            fail(path, "malformed header line '" + line.substr(0, 60) + "' (expected key=value)");
        }
        fields[toLower(trim(line.substr(0, eq)))] = trim(line.substr(eq + 1));
    }

    long long ndim = intField(path, fields, "ndim", 0, true);
    if (ndim != 3) fail(path, "ndim " + std::to_string(ndim) + " is not supported (need 3)");
    long long n[3];
    for (int a = 0; a < 3; ++a) n[a] = intField(path, fields, "dim" + std::to_string(a + 1), 0, true);
    checkedVoxelCount(path, "dims", n[0], n[1], n[2]);  // the bytes, once the type is known

    long long veclen = intField(path, fields, "veclen", 1, false);
    if (veclen != 1) fail(path, "veclen " + std::to_string(veclen) + " is not supported (need 1)");
    intField(path, fields, "nspace", 3, false);  // checked for form only

    auto dataIt = fields.find("data");
    if (dataIt == fields.end()) fail(path, "missing 'data' field");
    std::string data = toLower(dataIt->second);
    VoxelType type;
    if (data == "byte") type = VoxelType::UInt8;
    else if (data == "short") type = VoxelType::UInt16;
    else fail(path, "unsupported data type '" + dataIt->second + "' (supported: byte, short)");

    auto fieldIt = fields.find("field");
    if (fieldIt != fields.end() && toLower(fieldIt->second) != "uniform") {
        fail(path, "field '" + fieldIt->second + "' is not supported (need uniform)");
    }

    const std::uint64_t expected = checkedVolumeBytes(path, "dims", n[0], n[1], n[2], type);
    std::size_t elem = voxelTypeSize(type);
    std::vector<std::uint8_t> bytes = readRawVoxels(path, path, headerEnd + 2, expected);
    if (!hostIsLittleEndian()) swapByteOrder(bytes, elem);
    return buildVolume(path, glm::ivec3(int(n[0]), int(n[1]), int(n[2])), type, glm::dvec3(1.0),
                       std::move(bytes));
}

}  // namespace voxlab
