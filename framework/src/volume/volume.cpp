// voxlab: the Volume class — validation, value access, range and histogram.
#include "voxlab/volume.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "volume_io_util.h"

namespace voxlab {

const char* voxelTypeName(VoxelType type) {
    switch (type) {
        case VoxelType::UInt8: return "uint8";
        case VoxelType::UInt16: return "uint16";
        case VoxelType::Int16: return "int16";
        case VoxelType::Float32: return "float32";
    }
    return "unknown";
}

std::size_t voxelTypeSize(VoxelType type) {
    switch (type) {
        case VoxelType::UInt8: return 1;
        case VoxelType::UInt16: return 2;
        case VoxelType::Int16: return 2;
        case VoxelType::Float32: return 4;
    }
    return 0;
}

double Histogram::binWidth() const {
    return counts.empty() ? 0.0 : (hi - lo) / static_cast<double>(counts.size());
}

std::uint64_t Histogram::total() const {
    std::uint64_t sum = 0;
    for (std::uint64_t c : counts) sum += c;
    return sum;
}

namespace {

// Reads element `index` of type T from a byte buffer (memcpy: no aliasing
// or alignment assumptions).
template <typename T>
T load(const std::uint8_t* bytes, std::size_t index) {
    T v;
    std::memcpy(&v, bytes + index * sizeof(T), sizeof(T));
    return v;
}

// Voxels held in memory.
class MemoryStore final : public VoxelStore {
public:
    explicit MemoryStore(std::vector<std::uint8_t> bytes) : bytes_(std::move(bytes)) {}
    const std::uint8_t* data() const override { return bytes_.data(); }
    std::size_t size() const override { return bytes_.size(); }

private:
    std::vector<std::uint8_t> bytes_;
};

// Calls scan(first, count) over voxels [0, n) in slabs of about 64 MiB,
// letting go of each slab afterwards (a streamed volume keeps one slab
// resident however large it is).
template <class Scan>
void inSlabs(const VoxelStore& store, std::size_t n, std::size_t voxelSize, Scan scan) {
    const std::size_t slab = std::max<std::size_t>(1, (std::size_t(64) << 20) / voxelSize);
    for (std::size_t first = 0; first < n; first += slab) {
        const std::size_t count = std::min(slab, n - first);
        scan(first, count);
        store.release(first * voxelSize, count * voxelSize);
    }
}

template <typename T>
void integerRange(const VoxelStore& store, std::size_t n, double& lo, double& hi) {
    T mn = load<T>(store.data(), 0), mx = mn;
    inSlabs(store, n, sizeof(T), [&](std::size_t first, std::size_t count) {
        for (std::size_t i = first; i < first + count; ++i) {
            const T v = load<T>(store.data(), i);
            mn = std::min(mn, v);
            mx = std::max(mx, v);
        }
    });
    lo = mn;
    hi = mx;
}

std::string dimsText(glm::ivec3 d) {
    return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

}  // namespace

namespace {

// `text` as it may appear in a one-line message: control characters shown
// as '?', at most 40 characters.
std::string printable(const std::string& text) {
    std::string out = text.substr(0, 40);
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return text.size() > 40 ? out + "..." : out;
}

}  // namespace

std::uint64_t parseVolumeCapMiB(const std::string& text, const std::string& source) {
    long long mib = 0;
    if (!detail::parseInt(detail::trim(text), mib) || mib < 1 || std::uint64_t(mib) > kMaxVolumeCapMiB) {
        throw Error(source + ": expected a whole number of MiB from 1 to " + std::to_string(kMaxVolumeCapMiB) +
                    ", got '" + printable(text) + "'");
    }
    return std::uint64_t(mib);
}

std::uint64_t volumeCapMiB() {
    const char* value = std::getenv(kVolumeCapVariable);
    if (!value || !*value) return kDefaultVolumeCapMiB;
    return parseVolumeCapMiB(value, kVolumeCapVariable);
}

void VoxelStore::release(std::size_t, std::size_t) const {}

Volume::Volume(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
               std::vector<std::uint8_t> bytes, std::string name)
    : Volume(dims, type, spacing, std::make_shared<MemoryStore>(std::move(bytes)), std::move(name)) {}

Volume::Volume(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
               std::shared_ptr<const VoxelStore> store, std::string name)
    : name_(std::move(name)), dims_(dims), type_(type), spacing_(spacing), store_(std::move(store)) {
    const std::string label = name_.empty() ? "volume" : name_;
    auto problem = [&](const std::string& what) { throw detail::VolumeError(label, what); };

    if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0) {
        problem("dimensions must be positive, got " + dimsText(dims));
    }
    std::uint64_t count = std::uint64_t(dims.x) * std::uint64_t(dims.y) * std::uint64_t(dims.z);
    if (count > kMaxVoxels) {
        problem("dimensions " + dimsText(dims) + " exceed the limit of " +
                std::to_string(kMaxVoxels) + " voxels");
    }
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(spacing[a]) || spacing[a] <= 0.0) {
            std::ostringstream s;
            s << "spacing must be finite and positive, got " << spacing.x << " " << spacing.y
              << " " << spacing.z;
            problem(s.str());
        }
    }
    std::uint64_t expected = count * voxelTypeSize(type);
    const std::size_t have = store_ ? store_->size() : 0;
    if (have != expected) {
        problem("voxel data has " + std::to_string(have) + " bytes, expected " +
                std::to_string(expected) + " for " + dimsText(dims) + " " + voxelTypeName(type));
    }
    findRange(problem);
}

// The smallest and largest value, one slab at a time; a float voxel that is
// not finite is refused with its position.
template <class Problem>
void Volume::findRange(Problem problem) {
    const std::size_t n = voxelCount();
    const VoxelStore& store = *store_;
    switch (type_) {
        case VoxelType::UInt8: integerRange<std::uint8_t>(store, n, min_, max_); break;
        case VoxelType::UInt16: integerRange<std::uint16_t>(store, n, min_, max_); break;
        case VoxelType::Int16: integerRange<std::int16_t>(store, n, min_, max_); break;
        case VoxelType::Float32: {
            float mn = load<float>(store.data(), 0), mx = mn;
            inSlabs(store, n, sizeof(float), [&](std::size_t first, std::size_t count) {
                for (std::size_t i = first; i < first + count; ++i) {
                    const float v = load<float>(store.data(), i);
                    if (!std::isfinite(v)) {
                        const std::size_t x = i % std::size_t(dims_.x);
                        const std::size_t y = (i / std::size_t(dims_.x)) % std::size_t(dims_.y);
                        const std::size_t z = i / (std::size_t(dims_.x) * std::size_t(dims_.y));
                        problem(std::string("float32 voxel (") + std::to_string(x) + ", " + std::to_string(y) + ", " +
                                std::to_string(z) + ") is " + (std::isnan(v) ? "NaN" : "infinite") +
                                "; voxel values must be finite");
                    }
                    mn = std::min(mn, v);
                    mx = std::max(mx, v);
                }
            });
            min_ = mn;
            max_ = mx;
            break;
        }
    }
}

ByteView Volume::bytes() const {
    return store_ ? ByteView{store_->data(), store_->size()} : ByteView{};
}

void Volume::releaseSlices(int z0, int z1) const {
    if (!store_ || z1 <= z0) return;
    const std::size_t slice = std::size_t(dims_.x) * std::size_t(dims_.y) * voxelTypeSize(type_);
    store_->release(std::size_t(std::max(z0, 0)) * slice, std::size_t(z1 - std::max(z0, 0)) * slice);
}

void Volume::requireInMemory(const std::string& what) const {
    if (streamed())
        throw Error((name_.empty() ? std::string("volume") : name_) + ": " + what +
                    " needs the volume in memory, and it is streamed from " + streamedFrom() +
                    " (over the " + std::to_string(volumeCapMiB()) +
                    " MiB volume cap): raise --max-volume-mib if the machine has the memory");
}

std::size_t Volume::voxelCount() const {
    return std::size_t(dims_.x) * std::size_t(dims_.y) * std::size_t(dims_.z);
}

double Volume::minSpacing() const { return std::min({spacing_.x, spacing_.y, spacing_.z}); }

double Volume::valueAt(std::size_t index) const {
    assert(index < voxelCount());
    const std::uint8_t* p = store_->data();
    switch (type_) {
        case VoxelType::UInt8: return p[index];
        case VoxelType::UInt16: return load<std::uint16_t>(p, index);
        case VoxelType::Int16: return load<std::int16_t>(p, index);
        case VoxelType::Float32: return load<float>(p, index);
    }
    return 0.0;
}

double Volume::value(int i, int j, int k) const {
    assert(i >= 0 && j >= 0 && k >= 0 && i < dims_.x && j < dims_.y && k < dims_.z);
    return valueAt(std::size_t(i) + std::size_t(dims_.x) * (std::size_t(j) + std::size_t(dims_.y) * std::size_t(k)));
}

Histogram Volume::histogram(int bins) const {
    if (bins < 1 || bins > (1 << 24)) {
        throw Error("histogram: bins must be between 1 and 16777216, got " + std::to_string(bins));
    }
    Histogram h;
    h.lo = min_;
    h.hi = max_;
    h.counts.assign(static_cast<std::size_t>(bins), 0);
    const double w = h.binWidth();
    auto binOf = [&](double v) -> std::size_t {
        if (w <= 0.0) return 0;
        double b = std::floor((v - h.lo) / w);
        return static_cast<std::size_t>(std::clamp(b, 0.0, double(bins - 1)));
    };

    const std::size_t n = voxelCount();
    if (n == 0) return h;
    const std::size_t size = voxelTypeSize(type_);
    if (type_ == VoxelType::Float32) {
        inSlabs(*store_, n, size, [&](std::size_t first, std::size_t count) {
            for (std::size_t i = first; i < first + count; ++i) h.counts[binOf(valueAt(i))]++;
        });
        return h;
    }
    // Integer types: count each distinct value once, then bin the values.
    std::vector<std::uint64_t> perValue(type_ == VoxelType::UInt8 ? 256 : 65536, 0);
    const double offset = type_ == VoxelType::Int16 ? 32768.0 : 0.0;
    inSlabs(*store_, n, size, [&](std::size_t first, std::size_t count) {
        for (std::size_t i = first; i < first + count; ++i) perValue[static_cast<std::size_t>(valueAt(i) + offset)]++;
    });
    for (std::size_t v = 0; v < perValue.size(); ++v) {
        if (perValue[v]) h.counts[binOf(double(v) - offset)] += perValue[v];
    }
    return h;
}

}  // namespace voxlab
