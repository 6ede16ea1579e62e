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

template <typename T>
void integerRange(const std::vector<std::uint8_t>& bytes, std::size_t n, double& lo, double& hi) {
    T mn = load<T>(bytes.data(), 0), mx = mn;
    for (std::size_t i = 1; i < n; ++i) {
        T v = load<T>(bytes.data(), i);
        mn = std::min(mn, v);
        mx = std::max(mx, v);
    }
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

Volume::Volume(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing,
               std::vector<std::uint8_t> bytes, std::string name)
    : name_(std::move(name)), dims_(dims), type_(type), spacing_(spacing), bytes_(std::move(bytes)) {
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
    if (bytes_.size() != expected) {
        problem("voxel data has " + std::to_string(bytes_.size()) + " bytes, expected " +
                std::to_string(expected) + " for " + dimsText(dims) + " " + voxelTypeName(type));
    }

    const std::size_t n = static_cast<std::size_t>(count);
    switch (type) {
        case VoxelType::UInt8: integerRange<std::uint8_t>(bytes_, n, min_, max_); break;
        case VoxelType::UInt16: integerRange<std::uint16_t>(bytes_, n, min_, max_); break;
        case VoxelType::Int16: integerRange<std::int16_t>(bytes_, n, min_, max_); break;
        case VoxelType::Float32: {
            float mn = 0.0f, mx = 0.0f;
            for (std::size_t i = 0; i < n; ++i) {
                float v = load<float>(bytes_.data(), i);
                if (!std::isfinite(v)) {
                    std::size_t x = i % std::size_t(dims.x);
                    std::size_t y = (i / std::size_t(dims.x)) % std::size_t(dims.y);
                    std::size_t z = i / (std::size_t(dims.x) * std::size_t(dims.y));
                    problem(std::string("float32 voxel (") + std::to_string(x) + ", " +
                            std::to_string(y) + ", " + std::to_string(z) + ") is " +
                            (std::isnan(v) ? "NaN" : "infinite") +
                            "; voxel values must be finite");
                }
                if (i == 0 || v < mn) mn = v;
                if (i == 0 || v > mx) mx = v;
            }
            min_ = mn;
            max_ = mx;
            break;
        }
    }
}

std::size_t Volume::voxelCount() const {
    return std::size_t(dims_.x) * std::size_t(dims_.y) * std::size_t(dims_.z);
}

double Volume::minSpacing() const { return std::min({spacing_.x, spacing_.y, spacing_.z}); }

double Volume::valueAt(std::size_t index) const {
    assert(index < voxelCount());
    const std::uint8_t* p = bytes_.data();
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
    if (type_ == VoxelType::Float32) {
        for (std::size_t i = 0; i < n; ++i) h.counts[binOf(valueAt(i))]++;
        return h;
    }
    // Integer types: count each distinct value once, then bin the values.
    std::vector<std::uint64_t> perValue(type_ == VoxelType::UInt8 ? 256 : 65536, 0);
    const double offset = type_ == VoxelType::Int16 ? 32768.0 : 0.0;
    for (std::size_t i = 0; i < n; ++i) perValue[static_cast<std::size_t>(valueAt(i) + offset)]++;
    for (std::size_t v = 0; v < perValue.size(); ++v) {
        if (perValue[v]) h.counts[binOf(double(v) - offset)] += perValue[v];
    }
    return h;
}

}  // namespace voxlab
