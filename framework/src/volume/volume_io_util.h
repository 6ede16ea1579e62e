// voxlab (internal): helpers shared by the volume loaders.
//
// Every helper that can fail throws voxlab::Error with the one-line message
// "<path>: <problem>", where <path> is the file the user asked for (the
// header, for formats whose voxels live in a second file).
//
// Safety rules the loaders follow, with these helpers:
//  - headers and text descriptions are read through a size cap
//    (kMaxHeaderBytes), so a file that never ends its header cannot make us
//    read or allocate much;
//  - voxel counts from a header are checked against kMaxVoxels, and their
//    size in bytes against the volume cap (checkedVolumeBytes), before
//    anything is allocated;
//  - raw voxel data is checked against the real file size before it is read;
//  - gzip data is inflated into a buffer that grows as output arrives and
//    never past the expected size, so a tiny stream cannot trigger a huge
//    allocation up front, and a stream that inflates to more is stopped at
//    the first surplus byte.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "voxlab/error.h"
#include "voxlab/volume.h"

namespace voxlab::detail {

// Largest header (NRRD, AVS field) or text description (.dat) we read.
constexpr std::size_t kMaxHeaderBytes = 65536;

// Thrown by Volume's constructor. The message is "<label>: <problem>"; the
// loaders catch it and re-throw with their own path in front of problem().
class VolumeError : public Error {
public:
    VolumeError(const std::string& label, const std::string& problem)
        : Error(label + ": " + problem), problem_(problem) {}
    const std::string& problem() const { return problem_; }

private:
    std::string problem_;
};

[[noreturn]] void fail(const std::string& path, const std::string& problem);

// ---- files -----------------------------------------------------------------

// Size of a regular file. Throws "PATH: no such file" / "is a directory" /
// "cannot read file".
std::uint64_t fileSize(const std::string& path);

// The first min(fileSize, maxBytes) bytes of a file.
std::string readPrefix(const std::string& path, std::size_t maxBytes);

// Exactly `count` bytes starting at `offset`; the caller has checked that
// the file is long enough. `errorPath` names the file in messages.
std::vector<std::uint8_t> readBytes(const std::string& errorPath, const std::string& path,
                                    std::uint64_t offset, std::uint64_t count);

// Raw voxel data: the file `dataPath` must hold exactly `expected` bytes
// after `offset`. Too few gives "truncated data: expected N bytes, got M",
// too many "data is too long: expected N bytes, got M"; both name `errorPath`
// (and `dataPath` when it is a different file). Checked before allocating.
std::vector<std::uint8_t> readRawVoxels(const std::string& errorPath, const std::string& dataPath,
                                        std::uint64_t offset, std::uint64_t expected);
// readRawVoxels' length checks alone.
void checkRawLength(const std::string& errorPath, const std::string& dataPath, std::uint64_t offset,
                    std::uint64_t expected);

// ---- streaming (voxel_store.cpp) -------------------------------------------

// The `expected` bytes at `offset` of `dataPath` (after readRawVoxels'
// checks), mapped read-only: voxels in host byte order, streamed from the
// file.
std::shared_ptr<const VoxelStore> mapRawVoxels(const std::string& errorPath, const std::string& dataPath,
                                               std::uint64_t offset, std::uint64_t expected);
// Voxels that cannot be mapped as they are (gzip, or `swapElement` > 1:
// another byte order), written once into a cache file in host order and
// mapped from there. The cache file is named after the data file's path,
// size and time, and the region.
std::shared_ptr<const VoxelStore> streamThroughCache(const std::string& errorPath, const std::string& dataPath,
                                                     std::uint64_t offset, std::uint64_t skip, std::uint64_t expected,
                                                     bool gzip, std::size_t swapElement);
// Whether voxel data of `bytes` goes over the memory cap (then it is
// streamed where the format allows).
bool overMemoryCap(std::uint64_t bytes);
// The cap's message for a format that cannot stream.
[[noreturn]] void failOverCap(const std::string& path, long long nx, long long ny, long long nz, VoxelType type,
                              std::uint64_t bytes);

// `name` relative to the folder of `headerPath` (absolute names unchanged).
std::string siblingPath(const std::string& headerPath, const std::string& name);

// "bonsai" for ".../bonsai.nrrd".
std::string fileStem(const std::string& path);

// Lower-case extension with the dot (".nrrd"), or "".
std::string fileExtension(const std::string& path);

// ---- gzip ------------------------------------------------------------------

// Inflates the gzip (or zlib) stream that starts at `offset` in `dataPath`,
// drops the first `skip` output bytes and returns exactly the next
// `expected` bytes. The file is read in chunks. Errors (naming `errorPath`):
// "corrupt gzip data (<zlib message>)", "truncated data: expected N bytes,
// got M", "gzip data is too long: more than N bytes". Concatenated gzip
// members are accepted; bytes after the end of the stream once `expected`
// bytes are out are ignored. The output buffer grows with the data that
// arrives, never past `expected` (peak 1.125x, while the last growth
// copies), and inflation stops at the first byte beyond it.
std::vector<std::uint8_t> inflateGzipFile(const std::string& errorPath, const std::string& dataPath,
                                          std::uint64_t offset, std::uint64_t skip,
                                          std::uint64_t expected);
// The same handed to `sink` a few MiB at a time, in order (nothing is held).
void inflateGzipTo(const std::string& errorPath, const std::string& dataPath, std::uint64_t offset,
                   std::uint64_t skip, std::uint64_t expected,
                   const std::function<void(const std::uint8_t*, std::size_t)>& sink);

// ---- bytes and numbers -----------------------------------------------------

bool hostIsLittleEndian();
// Reverses the byte order of every `elementSize`-byte element in place.
void swapByteOrder(std::vector<std::uint8_t>& bytes, std::size_t elementSize);

// Whole-string, locale-independent parses (a leading '+' is allowed,
// surrounding spaces are not). parseDouble accepts "nan" and "inf".
bool parseInt(const std::string& text, long long& out);
bool parseDouble(const std::string& text, double& out);

std::string trim(const std::string& text);
std::string toLower(std::string text);
std::vector<std::string> splitWords(const std::string& text);

// nx*ny*nz after checking each is positive and the product is at most
// kMaxVoxels. `what` names the field in messages ("sizes", "dims", ...).
std::uint64_t checkedVoxelCount(const std::string& path, const std::string& what,
                                long long nx, long long ny, long long nz);

// The size of the voxel data in bytes, after checkedVoxelCount and against
// the volume cap (volume.h): "<path>: 1024x1024x2048 float32 is 8192 MiB,
// over the 4096 MiB volume cap (set VOXLAB_MAX_VOLUME_MIB to raise it)".
// Loaders call it once the type is known and before allocating anything.
std::uint64_t checkedVolumeBytes(const std::string& path, const std::string& what,
                                 long long nx, long long ny, long long nz, VoxelType type);

// Builds the Volume; a VolumeError from the constructor (e.g. a NaN voxel)
// is re-thrown as "<path>: <problem>".
Volume buildVolume(const std::string& path, glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
                   std::vector<std::uint8_t> bytes);
Volume buildVolume(const std::string& path, glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
                   std::shared_ptr<const VoxelStore> store);

}  // namespace voxlab::detail
