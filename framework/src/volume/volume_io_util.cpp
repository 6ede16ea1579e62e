// voxlab (internal): file, gzip, byte-order and number helpers for loaders.
#include "volume_io_util.h"
#include "voxlab/number_text.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstring>
#include <limits>
#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>

#include <zlib.h>

namespace fs = std::filesystem;

namespace voxlab::detail {

void fail(const std::string& path, const std::string& problem) {
    throw Error(path + ": " + problem);
}

// ---- files -----------------------------------------------------------------

std::uint64_t fileSize(const std::string& path) {
    std::error_code ec;
    fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) fail(path, "no such file");
    if (fs::is_directory(st)) fail(path, "is a directory, not a file");
    std::uintmax_t size = fs::file_size(path, ec);
    if (ec) fail(path, "cannot read file (" + ec.message() + ")");
    std::ifstream probe(path, std::ios::binary);
    if (!probe) fail(path, "cannot open file for reading");
    return size;
}

std::string readPrefix(const std::string& path, std::size_t maxBytes) {
    std::uint64_t size = fileSize(path);
    std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(size, maxBytes));
    std::string text(want, '\0');
    std::ifstream in(path, std::ios::binary);
    in.read(text.data(), static_cast<std::streamsize>(want));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text;
}

std::vector<std::uint8_t> readBytes(const std::string& errorPath, const std::string& path,
                                    std::uint64_t offset, std::uint64_t count) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(errorPath, "cannot open '" + path + "' for reading");
    in.seekg(static_cast<std::streamoff>(offset));
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(count));
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(count));
    auto got = static_cast<std::uint64_t>(std::max<std::streamsize>(in.gcount(), 0));
    if (got != count) {
        fail(errorPath, "truncated data: expected " + std::to_string(count) + " bytes, got " +
                            std::to_string(got));
    }
    return bytes;
}

std::vector<std::uint8_t> readRawVoxels(const std::string& errorPath, const std::string& dataPath,
                                        std::uint64_t offset, std::uint64_t expected) {
    checkRawLength(errorPath, dataPath, offset, expected);
    return readBytes(errorPath, dataPath, offset, expected);
}

void checkRawLength(const std::string& errorPath, const std::string& dataPath, std::uint64_t offset,
                    std::uint64_t expected) {
    std::uint64_t size = fileSize(dataPath);
    std::uint64_t available = size > offset ? size - offset : 0;
    std::string where =
        dataPath == errorPath ? "" : " in '" + fs::path(dataPath).filename().string() + "'";
    if (available < expected) {
        fail(errorPath, "truncated data" + where + ": expected " + std::to_string(expected) +
                            " bytes, got " + std::to_string(available));
    }
    if (available > expected) {
        fail(errorPath, "data is too long" + where + ": expected " + std::to_string(expected) +
                            " bytes, got " + std::to_string(available));
    }
}

std::string siblingPath(const std::string& headerPath, const std::string& name) {
    fs::path p(name);
    if (p.is_absolute()) return name;
    return (fs::path(headerPath).parent_path() / p).string();
}

std::string fileStem(const std::string& path) { return fs::path(path).stem().string(); }

std::string fileExtension(const std::string& path) {
    return toLower(fs::path(path).extension().string());
}

// ---- gzip ------------------------------------------------------------------

namespace {

// Output bookkeeping for inflateGzip: the first `skip` bytes go to a scratch
// buffer and are dropped, the next `expected` go to `out`, which grows as
// data arrives (grow()) and never past `expected`.
struct InflateTarget {
    std::uint64_t skip, expected;
    std::uint64_t skipped = 0, produced = 0;
    std::vector<std::uint8_t> out;
    // When set: output goes through `chunk` to the sink a chunk at a time,
    // instead of into `out`.
    std::function<void(const std::uint8_t*, std::size_t)> sink;
    std::vector<std::uint8_t> chunk;
    std::size_t filled = 0;
    std::uint8_t scratch[1 << 16];

    bool complete() const { return skipped == skip && produced == expected; }

    // Points the stream at where the next output should go. Once complete,
    // offers one byte of room so that surplus data can be detected.
    void aim(z_stream& zs) {
        if (skipped < skip) {
            zs.next_out = scratch;
            zs.avail_out = static_cast<uInt>(std::min<std::uint64_t>(sizeof scratch, skip - skipped));
        } else if (produced < expected && sink) {
            if (filled == chunk.size()) flush();
            zs.next_out = chunk.data() + filled;
            zs.avail_out = static_cast<uInt>(std::min<std::uint64_t>(chunk.size() - filled, expected - produced));
        } else if (produced < expected) {
            if (out.size() == produced) grow();
            zs.next_out = out.data() + produced;
            zs.avail_out = static_cast<uInt>(std::min<std::uint64_t>(out.size() - produced, 1u << 30));
        } else {
            zs.next_out = scratch;
            zs.avail_out = 1;
        }
    }

    // Makes room for more output. The memory follows the data that really
    // arrives (a stream that declares 3 GiB and holds 1 KiB costs 1 MiB): the
    // sizes are expected/2^k, each twice the last, at least 1 MiB, until
    // an eighth of `expected` has arrived; then the buffer grows once to
    // exactly `expected`. That last growth copies an eighth, so loading
    // peaks at 1.125 x the declared size (capped by checkedVolumeBytes), and
    // the buffer is never more than 8 x the data that has arrived.
    void grow() {
        if (out.size() * 8 >= expected) {
            out.reserve(static_cast<std::size_t>(expected));
            out.resize(static_cast<std::size_t>(expected));
            return;
        }
        const std::uint64_t wanted = std::max<std::uint64_t>(2 * out.size(), 1 << 20);
        std::uint64_t size = expected;
        while (size / 2 >= wanted) size /= 2;
        out.reserve(static_cast<std::size_t>(size));  // exactly this much, not the vector's own growth
        out.resize(static_cast<std::size_t>(size));
    }

    void flush() {
        if (filled > 0) sink(chunk.data(), filled);
        filled = 0;
    }

    // Records `n` bytes written since aim(); returns true if they were surplus.
    bool advance(std::uint64_t n) {
        if (skipped < skip) skipped += n;
        else if (produced < expected) produced += n, filled += sink ? std::size_t(n) : 0;
        else return n > 0;
        return false;
    }
};

}  // namespace

namespace {

// Inflates into `target` (its vector, or its sink).
void inflateInto(const std::string& errorPath, const std::string& dataPath, std::uint64_t offset,
                 InflateTarget* target) {
    const std::uint64_t expected = target->expected;
    std::ifstream in(dataPath, std::ios::binary);
    if (!in) fail(errorPath, "cannot open '" + dataPath + "' for reading");
    in.seekg(static_cast<std::streamoff>(offset));

    z_stream zs{};
    if (inflateInit2(&zs, 15 + 32) != Z_OK) fail(errorPath, "cannot initialise zlib");
    struct Guard { z_stream* zs; ~Guard() { inflateEnd(zs); } } guard{&zs};

    std::vector<std::uint8_t> input(1 << 18);
    bool inputDone = false;

    auto truncated = [&]() {
        fail(errorPath, "truncated data: expected " + std::to_string(expected) + " bytes, got " +
                            std::to_string(target->produced));
    };

    for (;;) {
        if (zs.avail_in == 0 && !inputDone) {
            in.read(reinterpret_cast<char*>(input.data()), static_cast<std::streamsize>(input.size()));
            std::streamsize got = in.gcount();
            if (got <= 0) inputDone = true;
            zs.next_in = input.data();
            zs.avail_in = static_cast<uInt>(std::max<std::streamsize>(got, 0));
        }
        target->aim(zs);
        uInt room = zs.avail_out;
        int ret = inflate(&zs, Z_NO_FLUSH);
        if (target->advance(room - zs.avail_out)) {
            fail(errorPath, "gzip data is too long: more than " + std::to_string(expected) +
                                " bytes");
        }
        if (ret == Z_STREAM_END) {
            if (target->complete()) break;
            if (zs.avail_in == 0 && in.peek() == std::char_traits<char>::eof()) truncated();
            inflateReset(&zs);  // another gzip member follows
            continue;
        }
        if (ret == Z_BUF_ERROR) {
            // No progress possible: zlib wants more input and there is none.
            if (zs.avail_in == 0 && inputDone) {
                if (target->complete()) {
                    fail(errorPath, "truncated data: gzip stream ends before its end marker");
                }
                truncated();
            }
            continue;
        }
        if (ret != Z_OK) {
            std::string msg = zs.msg ? zs.msg : "zlib error " + std::to_string(ret);
            fail(errorPath, "corrupt gzip data (" + msg + ")");
        }
    }
}

}  // namespace

std::vector<std::uint8_t> inflateGzipFile(const std::string& errorPath, const std::string& dataPath,
                                          std::uint64_t offset, std::uint64_t skip,
                                          std::uint64_t expected) {
    auto target = std::make_unique<InflateTarget>();
    target->skip = skip;
    target->expected = expected;
    inflateInto(errorPath, dataPath, offset, target.get());
    return std::move(target->out);
}

void inflateGzipTo(const std::string& errorPath, const std::string& dataPath, std::uint64_t offset,
                   std::uint64_t skip, std::uint64_t expected,
                   const std::function<void(const std::uint8_t*, std::size_t)>& sink) {
    auto target = std::make_unique<InflateTarget>();
    target->skip = skip;
    target->expected = expected;
    target->sink = sink;
    target->chunk.resize(std::size_t(4) << 20);
    inflateInto(errorPath, dataPath, offset, target.get());
    target->flush();
}

// ---- bytes and numbers -----------------------------------------------------

bool hostIsLittleEndian() {
    const std::uint16_t probe = 1;
    std::uint8_t first;
    std::memcpy(&first, &probe, 1);
    return first == 1;
}

void swapByteOrder(std::vector<std::uint8_t>& bytes, std::size_t elementSize) {
    if (elementSize < 2) return;
    for (std::size_t i = 0; i + elementSize <= bytes.size(); i += elementSize) {
        std::reverse(bytes.begin() + static_cast<std::ptrdiff_t>(i),
                     bytes.begin() + static_cast<std::ptrdiff_t>(i + elementSize));
    }
}

namespace {
const char* skipPlus(const std::string& text) {
    const char* p = text.data();
    if (text.size() > 1 && *p == '+' && p[1] != '-') ++p;
    return p;
}
}  // namespace

bool parseInt(const std::string& text, long long& out) {
    if (text.empty()) return false;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(skipPlus(text), end, out);
    return ec == std::errc() && ptr == end;
}

bool parseDouble(const std::string& text, double& out) {
    if (text.empty()) return false;
    return parseDoubleExactly(skipPlus(text), text.data() + text.size(), &out);
}

std::string trim(const std::string& text) {
    auto isSpace = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
    std::size_t b = 0, e = text.size();
    while (b < e && isSpace(text[b])) ++b;
    while (e > b && isSpace(text[e - 1])) --e;
    return text.substr(b, e - b);
}

std::string toLower(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

std::vector<std::string> splitWords(const std::string& text) {
    std::vector<std::string> words;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        std::size_t start = i;
        while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        if (i > start) words.push_back(text.substr(start, i - start));
    }
    return words;
}

std::uint64_t checkedVoxelCount(const std::string& path, const std::string& what,
                                long long nx, long long ny, long long nz) {
    std::string listed = std::to_string(nx) + " " + std::to_string(ny) + " " + std::to_string(nz);
    if (nx <= 0 || ny <= 0 || nz <= 0) fail(path, what + " must be positive, got " + listed);
    auto tooMany = [&]() {
        fail(path, what + " " + listed + " exceed the limit of " + std::to_string(kMaxVoxels) +
                       " voxels");
    };
    std::uint64_t count = 1;
    for (long long n : {nx, ny, nz}) {
        // Each size becomes an int (glm::ivec3): 2^31 itself would wrap to a
        // negative size after the data was read.
        if (n > std::numeric_limits<int>::max()) tooMany();
        count *= static_cast<std::uint64_t>(n);  // at most 2^44 times 2^31: no overflow
        if (count > kMaxVoxels) tooMany();
    }
    return count;
}

bool overMemoryCap(std::uint64_t bytes) { return bytes > volumeCapMiB() * (std::uint64_t(1) << 20); }

void failOverCap(const std::string& path, long long nx, long long ny, long long nz, VoxelType type,
                 std::uint64_t bytes) {
    const std::uint64_t capMiB = volumeCapMiB(), mib = std::uint64_t(1) << 20;
    const std::string size = bytes % mib == 0 ? std::to_string(bytes / mib) + " MiB" : std::to_string(bytes) + " bytes";
    fail(path, std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz) + " " + voxelTypeName(type) +
                   " is " + size + ", over the " + std::to_string(capMiB) + " MiB volume cap (set " +
                   kVolumeCapVariable + " to raise it)");
}

std::uint64_t checkedVolumeBytes(const std::string& path, const std::string& what,
                                 long long nx, long long ny, long long nz, VoxelType type) {
    const std::uint64_t bytes = checkedVoxelCount(path, what, nx, ny, nz) * voxelTypeSize(type);
    if (overMemoryCap(bytes)) failOverCap(path, nx, ny, nz, type, bytes);
    return bytes;
}

Volume buildVolume(const std::string& path, glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
                   std::vector<std::uint8_t> bytes) {
    try {
        return Volume(dims, type, spacing, std::move(bytes), fileStem(path));
    } catch (const VolumeError& e) {
        fail(path, e.problem());
    }
}

Volume buildVolume(const std::string& path, glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
                   std::shared_ptr<const VoxelStore> store) {
    try {
        return Volume(dims, type, spacing, std::move(store), fileStem(path));
    } catch (const VolumeError& e) {
        fail(path, e.problem());
    }
}

}  // namespace voxlab::detail
