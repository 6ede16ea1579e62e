// voxlab: a scalar volume on a regular grid, in its own value range.
//
// Layout: x varies fastest, then y, then z. Voxel (i,j,k) lives at index
// i + nx*(j + ny*k) and its centre is at world position
// ((i+1/2)*sx, (j+1/2)*sy, (k+1/2)*sz); the volume's box is [0, n*s] on each
// axis (see "Rendering conventions" in the README).
//
// Values keep their native type and range: a 12-bit CT stored as uint16 has
// values 0..4095, a signed CT stays signed. Nothing is rescaled to 0..255.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace voxlab {

enum class VoxelType { UInt8, UInt16, Int16, Float32 };

// "uint8", "uint16", "int16", "float32".
const char* voxelTypeName(VoxelType type);
std::size_t voxelTypeSize(VoxelType type);

// Counts of voxel values in `bins` equal-width bins spanning [lo, hi].
// Bin b covers [lo + b*w, lo + (b+1)*w) with w = (hi-lo)/bins; the value hi
// falls in the last bin. When lo == hi every voxel is in bin 0.
struct Histogram {
    double lo = 0.0;
    double hi = 0.0;
    std::vector<std::uint64_t> counts;

    double binWidth() const;
    std::uint64_t total() const;
};

// The largest grid voxlab accepts, in voxels (2^44, 16 Ti-voxels: far past
// any disk, and small enough that byte counts of float voxels cannot
// overflow). Each size must also fit an int. Loaders refuse anything larger
// before allocating, with a one-line error. What really bounds a volume is
// memory: the cap below, then the disk (streamed volumes).
constexpr std::uint64_t kMaxVoxels = std::uint64_t(1) << 44;

// The memory cap on a volume's voxel data held in memory, checked by the
// loaders and the phantoms against the declared size before anything is
// allocated: 4 GiB by default, or the whole number of MiB in the
// environment variable VOXLAB_MAX_VOLUME_MIB (1..kMaxVolumeCapMiB; empty
// counts as unset). The command line's --max-volume-mib (render, view,
// bench, info) sets that variable; child processes (the grader's workers)
// inherit it. Precomputed gradients answer to it too. A raw or NRRD volume
// over the cap is not refused but streamed from its file (VoxelStore
// below); a format that cannot be streamed (DICOM, .fld, a phantom) is
// refused: "big.fld: 1024x1024x2048 float32 is 8192 MiB, over the 4096 MiB
// volume cap (set VOXLAB_MAX_VOLUME_MIB to raise it)".
constexpr std::uint64_t kDefaultVolumeCapMiB = 4096;
constexpr std::uint64_t kMaxVolumeCapMiB = std::uint64_t(1) << 20;  // 1 TiB: beyond any real machine
constexpr const char* kVolumeCapVariable = "VOXLAB_MAX_VOLUME_MIB";

// The cap in MiB, read from the environment on each call (so that tests and
// the command line can change it). Throws voxlab::Error naming the variable
// when its value is not a whole number in 1..kMaxVolumeCapMiB.
std::uint64_t volumeCapMiB();
// Parses a cap given in MiB; `source` names where it came from in errors
// ("VOXLAB_MAX_VOLUME_MIB", "option --max-volume-mib").
std::uint64_t parseVolumeCapMiB(const std::string& text, const std::string& source);

// Where a volume's voxel bytes live: in memory, or in a file mapped
// read-only (a raw or NRRD volume over the memory cap, read page by page as
// it is drawn). release() lets go of pages that were read, so that going
// through a volume larger than memory keeps only a slab of it resident.
class VoxelStore {
public:
    virtual ~VoxelStore() = default;
    virtual const std::uint8_t* data() const = 0;
    virtual std::size_t size() const = 0;
    // Drops [offset, offset + length) from memory where it can be read again
    // (a mapped file); a store in memory keeps it.
    virtual void release(std::size_t offset, std::size_t length) const;
    // A file's path when the voxels are streamed from it, else "".
    virtual std::string streamedFrom() const { return ""; }
};

// A read-only view of bytes (a volume's voxels, wherever they live).
struct ByteView {
    const std::uint8_t* p = nullptr;
    std::size_t n = 0;
    const std::uint8_t* data() const { return p; }
    std::size_t size() const { return n; }
    bool empty() const { return n == 0; }
    const std::uint8_t* begin() const { return p; }
    const std::uint8_t* end() const { return p + n; }
    std::uint8_t operator[](std::size_t i) const { return p[i]; }
    std::vector<std::uint8_t> copy() const { return {p, p + n}; }
};
inline bool operator==(const ByteView& a, const std::vector<std::uint8_t>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}
inline bool operator==(const std::vector<std::uint8_t>& b, const ByteView& a) { return a == b; }
inline bool operator==(const ByteView& a, const ByteView& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}

class Volume {
public:
    Volume() = default;
    // `bytes` holds dims.x*dims.y*dims.z voxels of `type`, little-endian
    // (host order), x fastest. Throws voxlab::Error when the sizes disagree
    // or a dimension/spacing is not positive.
    Volume(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
           std::vector<std::uint8_t> bytes, std::string name = "");
    // The same over voxels that live elsewhere (a mapped file).
    Volume(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
           std::shared_ptr<const VoxelStore> store, std::string name = "");

    const std::string& name() const { return name_; }
    glm::ivec3 dims() const { return dims_; }
    VoxelType type() const { return type_; }
    glm::dvec3 spacing() const { return spacing_; }
    std::size_t voxelCount() const;
    ByteView bytes() const;
    const void* data() const { return bytes().data(); }
    // Streamed from a file (over the memory cap): the file's path, else "".
    std::string streamedFrom() const { return store_ ? store_->streamedFrom() : ""; }
    bool streamed() const { return !streamedFrom().empty(); }
    // Lets go of the voxels of z-slices [z0, z1) where a streamed volume
    // can read them again; nothing for a volume in memory.
    void releaseSlices(int z0, int z1) const;
    // Throws voxlab::Error naming `what` (a renderer's whole-volume copy,
    // "shear-warp's slice stacks") when the volume is streamed: it needs
    // the volume in memory.
    void requireInMemory(const std::string& what) const;

    // World-space size of the box: dims * spacing.
    glm::dvec3 extent() const { return glm::dvec3(dims_) * spacing_; }
    double minSpacing() const;

    // The value of voxel (i,j,k) in the data's own units. No bounds check
    // beyond an assert: callers clamp.
    double value(int i, int j, int k) const;
    double valueAt(std::size_t index) const;

    // Smallest and largest voxel value (computed once, at construction).
    double minValue() const { return min_; }
    double maxValue() const { return max_; }
    glm::dvec2 valueRange() const { return {min_, max_}; }

    // Histogram over [minValue, maxValue].
    Histogram histogram(int bins = 256) const;

    // What the loader learnt about where the voxels came from, as ordered
    // (key, value) pairs that `voxlab info` prints one per line: a DICOM
    // series gives its Series Description, Modality, slices, orientation and
    // rescale. Empty for formats that carry nothing of the kind.
    using Metadata = std::vector<std::pair<std::string, std::string>>;
    const Metadata& metadata() const { return metadata_; }
    void setMetadata(Metadata metadata) { metadata_ = std::move(metadata); }

private:
    template <class Problem>
    void findRange(Problem problem);

    std::string name_;
    glm::ivec3 dims_{0};
    VoxelType type_ = VoxelType::UInt8;
    glm::dvec3 spacing_{1.0};
    std::shared_ptr<const VoxelStore> store_;
    double min_ = 0.0;
    double max_ = 0.0;
    Metadata metadata_;
};

// Loads a volume from a path or a phantom spec, choosing the loader by
// extension (.nrrd/.nhdr, .fld, .dat) or the "phantom:" prefix. A folder, a
// .dcm/.dicom/.ima file, and any other file whose bytes 128..131 are "DICM"
// go to loadDicom. Throws voxlab::Error with a one-line message naming the
// file and the problem.
Volume loadVolume(const std::string& pathOrSpec);

// Individual loaders (see framework/src/volume/).
Volume loadNrrd(const std::string& path);
Volume loadFld(const std::string& path);
Volume loadDatRaw(const std::string& path);

// A DICOM CT/MR series, read through GDCM (framework/src/volume/dicom_loader.cpp).
// `path` is a folder holding one series, or any one file of a series (the
// series is then that file's Series Instance UID among the files beside it).
// Voxel layout: x = DICOM columns, y = rows (Pixel Spacing's second and first
// value), z = slices in increasing position along the slice normal
// (row cosine x column cosine), whatever the files' names or Instance
// Numbers. Values are rescaled by Rescale Slope/Intercept (Hounsfield units
// for CT): int16 when every value is then an integer in int16's range, else
// float32; without a rescale, 8-bit data stays uint8 and 16-bit data uint16 or
// int16 (Pixel Representation). An oblique series is loaded on its own axes.
// The volume's metadata() names the series, modality, slices, orientation
// and rescale. A mixed or incomplete series, a transfer syntax GDCM cannot
// decode, a missing tag, a single slice or a size over the volume cap give a
// one-line voxlab::Error that starts with `path`.
Volume loadDicom(const std::string& path);

// Writes an attached, raw (or gzip) NRRD through writeFileAtomically (a
// failed save leaves the old file). Used by tests and tools.
void saveNrrd(const Volume& volume, const std::string& path, bool gzip = false);

// Built-in analytic phantoms, addressed as "phantom:NAME[:SIZE]" (SIZE is
// the edge length in voxels, default 64). See phantoms.h for the formulas.
Volume makePhantom(const std::string& spec);
std::vector<std::string> phantomNames();

}  // namespace voxlab
