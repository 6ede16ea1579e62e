// voxlab: voxels streamed from a file (VoxelStore, volume.h): a raw or NRRD
// volume over the memory cap is mapped read-only and read page by page as
// it is drawn; what was read is let go again (madvise), so a volume larger
// than the machine's memory is drawn with a slab of it resident. A gzip or
// big-endian file cannot be mapped as it is: it is inflated or swapped once
// into a cache file ($XDG_CACHE_HOME/voxlab/streamed, else
// ~/.cache/voxlab/streamed), which is then mapped.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <filesystem>
#include <functional>

#include "volume_io_util.h"

namespace voxlab::detail {

namespace {

namespace fs = std::filesystem;

std::size_t pageSize() {
    static const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE) > 0 ? sysconf(_SC_PAGESIZE) : 4096);
    return page;
}

// [offset, offset + bytes) of a file, mapped read-only.
class MappedStore final : public VoxelStore {
public:
    MappedStore(const std::string& errorPath, const std::string& path, std::uint64_t offset, std::uint64_t bytes)
        : path_(path), bytes_(std::size_t(bytes)) {
        const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) fail(errorPath, "cannot open '" + path + "' for reading: " + std::strerror(errno));
        lead_ = std::size_t(offset % pageSize());
        length_ = bytes_ + lead_;
        void* at = mmap(nullptr, length_, PROT_READ, MAP_PRIVATE, fd, off_t(offset - lead_));
        const int err = errno;
        close(fd);
        if (at == MAP_FAILED) fail(errorPath, "cannot map '" + path + "': " + std::strerror(err));
        base_ = static_cast<std::uint8_t*>(at);
    }
    ~MappedStore() override { munmap(base_, length_); }
    MappedStore(const MappedStore&) = delete;
    MappedStore& operator=(const MappedStore&) = delete;

    const std::uint8_t* data() const override { return base_ + lead_; }
    std::size_t size() const override { return bytes_; }
    std::string streamedFrom() const override { return path_; }
    // Whole pages inside the range only: a page shared with voxels still in
    // use stays.
    void release(std::size_t offset, std::size_t length) const override {
        const std::size_t page = pageSize();
        std::size_t first = lead_ + offset, last = std::min(lead_ + offset + length, length_);
        first = (first + page - 1) / page * page;
        last = last / page * page;
        if (last > first) madvise(base_ + first, last - first, MADV_DONTNEED);
    }

private:
    std::string path_;
    std::size_t bytes_ = 0, lead_ = 0, length_ = 0;
    std::uint8_t* base_ = nullptr;
};

std::string cacheFolder() {
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    const fs::path base = xdg && *xdg ? fs::path(xdg) : home && *home ? fs::path(home) / ".cache" : fs::temp_directory_path();
    return (base / "voxlab" / "streamed").string();
}

// FNV-1a over what identifies the cache file's contents.
std::string cacheName(const std::string& dataPath, std::uint64_t offset, std::uint64_t skip, std::uint64_t bytes,
                      const std::string& how) {
    struct stat st {};
    stat(dataPath.c_str(), &st);
    const std::string key = fs::absolute(dataPath).string() + "|" + std::to_string(st.st_size) + "|" +
                            std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec) + "|" +
                            std::to_string(offset) + "|" + std::to_string(skip) + "|" + std::to_string(bytes) + "|" + how;
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : key) h = (h ^ c) * 1099511628211ull;
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.raw", static_cast<unsigned long long>(h));
    return name;
}

// Writes the cache file at `target` from what `fill` hands its sink, in
// order, in host byte order (each `swapElement`-byte value reversed), then
// renames it into place, so a half-written one is never used. Written a
// chunk at a time: nothing but a chunk is held.
void writeCacheFile(const std::string& errorPath, const fs::path& target, std::size_t swapElement,
                    const std::function<void(const std::function<void(const std::uint8_t*, std::size_t)>&)>& fill) {
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    const fs::path temp = target.string() + ".part" + std::to_string(getpid());
    const int fd = open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) fail(errorPath, "cannot write the streaming cache '" + temp.string() + "': " + std::strerror(errno));
    std::vector<std::uint8_t> swapped;
    std::uint64_t written = 0;
    auto sink = [&](const std::uint8_t* data, std::size_t n) {
        if (swapElement > 1) {  // chunks hold whole values: sizes and offsets are multiples of the element
            swapped.assign(data, data + n);
            for (std::size_t at = 0; at + swapElement <= n; at += swapElement)
                std::reverse(swapped.begin() + std::ptrdiff_t(at), swapped.begin() + std::ptrdiff_t(at + swapElement));
            data = swapped.data();
        }
        for (std::size_t done = 0; done < n;) {
            const ssize_t w = write(fd, data + done, n - done);
            if (w <= 0) fail(errorPath, "cannot write the streaming cache '" + temp.string() + "': " + std::strerror(errno));
            done += std::size_t(w);
        }
        written += n;
        // What is written is the page cache's: the process holds none of it.
        posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED);
    };
    try {
        fill(sink);
    } catch (...) {
        close(fd);
        fs::remove(temp, ec);
        throw;
    }
    const bool ok = fsync(fd) == 0;
    close(fd);
    if (ok) fs::rename(temp, target, ec);
    if (!ok || ec) {
        fs::remove(temp, ec);
        fail(errorPath, "cannot keep the streaming cache '" + target.string() + "'");
    }
}

// Refuses a cache file larger than the disk holds (less a GiB), before any
// of it is written. (A ratio bound would refuse real data: a label volume's
// gzip packs thousands of times.)
void checkCacheable(const std::string& errorPath, const std::string& folder, std::uint64_t expected) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    const fs::space_info space = fs::space(folder, ec);
    if (!ec && space.available < expected + (std::uint64_t(1) << 30))
        fail(errorPath, "streaming it needs a cache of " + std::to_string(expected >> 20) + " MiB in " + folder +
                            ", which has " + std::to_string(space.available >> 20) + " MiB free");
}

}  // namespace

std::shared_ptr<const VoxelStore> mapRawVoxels(const std::string& errorPath, const std::string& dataPath,
                                               std::uint64_t offset, std::uint64_t expected) {
    checkRawLength(errorPath, dataPath, offset, expected);
    return std::make_shared<MappedStore>(errorPath, dataPath, offset, expected);
}

std::shared_ptr<const VoxelStore> streamThroughCache(const std::string& errorPath, const std::string& dataPath,
                                                     std::uint64_t offset, std::uint64_t skip, std::uint64_t expected,
                                                     bool gzip, std::size_t swapElement) {
    const fs::path target = fs::path(cacheFolder()) /
                            cacheName(dataPath, offset, skip, expected, (gzip ? "gzip" : "raw") + std::to_string(swapElement));
    std::error_code ec;
    if (!fs::exists(target, ec) || fs::file_size(target, ec) != expected) {
        if (!gzip) checkRawLength(errorPath, dataPath, offset + skip, expected);
        checkCacheable(errorPath, target.parent_path().string(), expected);
        writeCacheFile(errorPath, target, swapElement, [&](const auto& sink) {
            if (gzip) {
                inflateGzipTo(errorPath, dataPath, offset, skip, expected, sink);
                return;
            }
            const std::shared_ptr<const VoxelStore> in = mapRawVoxels(errorPath, dataPath, offset + skip, expected);
            const std::uint64_t slab = std::uint64_t(4) << 20;
            for (std::uint64_t at = 0; at < expected; at += slab) {
                const std::size_t n = std::size_t(std::min(slab, expected - at));
                sink(in->data() + at, n);
                in->release(std::size_t(at), n);
            }
        });
    }
    return std::make_shared<MappedStore>(errorPath, target.string(), 0, expected);
}

}  // namespace voxlab::detail
