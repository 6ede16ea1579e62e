// voxlab: analytic phantoms (formulas documented in voxlab/phantoms.h).
#include "voxlab/phantoms.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "volume_io_util.h"

namespace voxlab {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Maps voxel index i of n to the centre of its cell in [-1, 1].
double normalised(int i, int n) { return -1.0 + 2.0 * (i + 0.5) / n; }

void storeFloat(std::vector<std::uint8_t>& bytes, std::size_t index, float v) {
    std::memcpy(bytes.data() + index * sizeof(float), &v, sizeof(float));
}

float loadFloat(const std::vector<std::uint8_t>& bytes, std::size_t index) {
    float v;
    std::memcpy(&v, bytes.data() + index * sizeof(float), sizeof(float));
    return v;
}

Volume floatVolume(const std::string& name, int n, std::vector<std::uint8_t> bytes) {
    return Volume(glm::ivec3(n), VoxelType::Float32, glm::dvec3(1.0), std::move(bytes), name);
}

// Evaluates f(i, j, k) at every voxel into a float32 volume.
template <typename F>
Volume floatVolume(const std::string& name, int n, F f) {
    std::vector<std::uint8_t> bytes(std::size_t(n) * n * n * sizeof(float));
    std::size_t idx = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) storeFloat(bytes, idx++, static_cast<float>(f(i, j, k)));
    return floatVolume(name, n, std::move(bytes));
}

Volume makeShells(const std::string& name, int n) {
    const double c = n / 2.0, half = shellsPhantomThickness(n) / 2.0;
    const double radii[3] = {0.15 * n, 0.28 * n, 0.42 * n};
    const std::uint8_t values[3] = {80, 160, 240};
    std::vector<std::uint8_t> bytes(std::size_t(n) * n * n, 0);
    std::size_t idx = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i, ++idx) {
                double r = glm::length(glm::dvec3(i + 0.5, j + 0.5, k + 0.5) - c);
                for (int s = 0; s < 3; ++s)
                    if (std::fabs(r - radii[s]) <= half) bytes[idx] = values[s];
            }
    return Volume(glm::ivec3(n), VoxelType::UInt8, glm::dvec3(1.0), std::move(bytes), name);
}

Volume makeCtSigned(const std::string& name, int n) {
    std::vector<std::uint8_t> bytes(std::size_t(n) * n * n * sizeof(std::int16_t));
    std::size_t idx = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i, ++idx) {
                const std::int16_t v = std::int16_t(ctSignedPhantomValue(n, {i + 0.5, j + 0.5, k + 0.5}));
                std::memcpy(bytes.data() + idx * sizeof v, &v, sizeof v);
            }
    return Volume(glm::ivec3(n), VoxelType::Int16, glm::dvec3(1.0), std::move(bytes), name);
}

// S. R. Marschner and R. J. Lobb, "An evaluation of reconstruction filters
// for volume rendering", Proc. IEEE Visualization '94, pp. 100-107.
// The signal is a sum of a z part and a radial (x, y) part, so the
// trigonometry is evaluated once per slice and once per column.
double marschnerLobbZ(double z) { return 1.0 - std::sin(kPi * z / 2.0); }
double marschnerLobbRadial(double x, double y) {
    const double r = std::sqrt(x * x + y * y);
    const double rhoR = std::cos(2.0 * kPi * kMarschnerLobbFM * std::cos(kPi * r / 2.0));
    return kMarschnerLobbAlpha * (1.0 + rhoR);
}
constexpr double kMarschnerLobbScale = 1.0 / (2.0 * (1.0 + kMarschnerLobbAlpha));

Volume makeMarschnerLobb(const std::string& name, int n) {
    std::vector<double> zPart(n), radial(std::size_t(n) * n);
    for (int k = 0; k < n; ++k) zPart[k] = marschnerLobbZ(normalised(k, n));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            radial[std::size_t(j) * n + i] = marschnerLobbRadial(normalised(i, n), normalised(j, n));
    return floatVolume(name, n, [&](int i, int j, int k) {
        return (zPart[k] + radial[std::size_t(j) * n + i]) * kMarschnerLobbScale;
    });
}

// One ellipsoid of the Shepp-Logan head: centre, semi-axes, rotation about
// the z axis (degrees, counter-clockwise from x) and the density it adds.
struct Ellipsoid {
    glm::dvec3 centre, axes;
    double phiDegrees, density;

    bool contains(glm::dvec3 q) const {
        const double phi = phiDegrees * kPi / 180.0;
        const glm::dvec3 d = q - centre;
        const double u = (d.x * std::cos(phi) + d.y * std::sin(phi)) / axes.x;
        const double v = (-d.x * std::sin(phi) + d.y * std::cos(phi)) / axes.y;
        const double w = d.z / axes.z;
        return u * u + v * v + w * w <= 1.0;
    }
};

// The 3D extension of Shepp & Logan's head section ("The Fourier
// reconstruction of a head section", IEEE Trans. Nucl. Sci. 21(3), 1974)
// as given by Kak & Slaney ("Principles of Computerized Tomographic
// Imaging", IEEE Press, 1988), with the higher-contrast "modified"
// densities of Toft ("The Radon Transform", PhD thesis, DTU, 1996). The
// two ventricles are rotated about z only.
const Ellipsoid kSheppLogan[] = {
    {{0.00, 0.0000, 0.00}, {0.6900, 0.920, 0.810}, 0.0, 1.0},    // skull
    {{0.00, -0.0184, 0.00}, {0.6624, 0.874, 0.780}, 0.0, -0.8},  // brain
    {{0.22, 0.0000, 0.00}, {0.1100, 0.310, 0.220}, -18.0, -0.2}, // right ventricle
    {{-0.22, 0.0000, 0.00}, {0.1600, 0.410, 0.280}, 18.0, -0.2}, // left ventricle
    {{0.00, 0.3500, -0.15}, {0.2100, 0.250, 0.410}, 0.0, 0.1},
    {{0.00, 0.1000, 0.25}, {0.0460, 0.046, 0.050}, 0.0, 0.1},
    {{0.00, -0.1000, 0.25}, {0.0460, 0.046, 0.050}, 0.0, 0.1},
    {{-0.08, -0.6050, 0.00}, {0.0460, 0.023, 0.050}, 0.0, 0.1},
    {{0.00, -0.6060, 0.00}, {0.0230, 0.023, 0.020}, 0.0, 0.1},
    {{0.06, -0.6050, 0.00}, {0.0230, 0.046, 0.020}, 0.0, 0.1},
};

// Index range [lo, hi] of the voxels whose centres can lie within
// [centre - radius, centre + radius] (normalised coordinates).
glm::ivec2 voxelRange(double centre, double radius, int n) {
    int lo = int(std::floor((centre - radius + 1.0) * n / 2.0 - 0.5)) - 1;
    int hi = int(std::ceil((centre + radius + 1.0) * n / 2.0 - 0.5)) + 1;
    return {std::max(lo, 0), std::min(hi, n - 1)};
}

// Adds each ellipsoid's density over the voxels of its bounding box, then
// clamps to >= 0. Same values as sheppLoganValue up to float rounding.
Volume makeSheppLogan(const std::string& name, int n) {
    std::vector<std::uint8_t> bytes(std::size_t(n) * n * n * sizeof(float), 0);
    for (const Ellipsoid& e : kSheppLogan) {
        const double rxy = std::max(e.axes.x, e.axes.y);  // any rotation about z
        glm::ivec2 ri = voxelRange(e.centre.x, rxy, n), rj = voxelRange(e.centre.y, rxy, n);
        glm::ivec2 rk = voxelRange(e.centre.z, e.axes.z, n);
        for (int k = rk.x; k <= rk.y; ++k)
            for (int j = rj.x; j <= rj.y; ++j)
                for (int i = ri.x; i <= ri.y; ++i) {
                    if (!e.contains({normalised(i, n), normalised(j, n), normalised(k, n)})) continue;
                    std::size_t idx = std::size_t(i) + std::size_t(n) * (j + std::size_t(n) * k);
                    storeFloat(bytes, idx, loadFloat(bytes, idx) + float(e.density));
                }
    }
    for (std::size_t idx = 0; idx < std::size_t(n) * n * n; ++idx)
        storeFloat(bytes, idx, std::max(loadFloat(bytes, idx), 0.0f));
    return floatVolume(name, n, std::move(bytes));
}

}  // namespace

double spherePhantomValue(int n, glm::dvec3 p) {
    double r = glm::length(p - glm::dvec3(n / 2.0));
    return std::clamp(0.5 + (spherePhantomRadius(n) - r) / kSpherePhantomWidth, 0.0, 1.0);
}

double sphereOverSlabValue(int n, glm::dvec3 p) {
    if (p.z >= 0.10 * n && p.z <= 0.25 * n) return 1.0;
    return glm::length(p - sphereOverSlabCentre(n)) <= sphereOverSlabRadius(n) ? 0.5 : 0.0;
}

int ctSignedPhantomValue(int n, glm::dvec3 p) {
    const glm::dvec3 c(n / 2.0);
    const double r = glm::length(p - c);
    if (glm::length(p - (c + glm::dvec3(0.32 * n, 0.0, 0.0))) <= 0.08 * n) return -800;  // the air pocket
    if (r <= 0.25 * n) return 700;
    if (r <= 0.40 * n) return -100;
    if (r <= 0.45 * n) return 40;
    return -1000;
}

int nestedLabelsValue(int n, glm::dvec3 p) {
    const glm::dvec3 c(n / 2.0);
    if (glm::length(p - (c + glm::dvec3(0.12 * n, 0.0, 0.0))) <= 0.18 * n) return 2;
    return glm::length(p - c) <= 0.40 * n ? 1 : 0;
}

double marschnerLobbValue(double x, double y, double z) {
    return (marschnerLobbZ(z) + marschnerLobbRadial(x, y)) * kMarschnerLobbScale;
}

double sheppLoganValue(glm::dvec3 q) {
    double sum = 0.0;
    for (const Ellipsoid& e : kSheppLogan)
        if (e.contains(q)) sum += e.density;
    return std::max(sum, 0.0);
}

std::vector<std::string> phantomNames() {
    return {"sphere", "shells", "ct-signed", "marschner-lobb", "shepp-logan", "sphere-over-slab", "nested-labels", "ramp-x", "ramp-y", "ramp-z"};
}

Volume makePhantom(const std::string& spec) {
    std::string rest = spec.rfind("phantom:", 0) == 0 ? spec.substr(8) : spec;
    std::size_t colon = rest.find(':');
    std::string name = rest.substr(0, colon);
    int n = kPhantomDefaultSize;
    if (colon != std::string::npos) {
        std::string sizeText = rest.substr(colon + 1);
        long long v;
        if (!detail::parseInt(sizeText, v)) {
            detail::fail(spec, "invalid size '" + sizeText + "' (need an integer " +
                                   std::to_string(kPhantomMinSize) + ".." +
                                   std::to_string(kPhantomMaxSize) + ")");
        }
        if (v < kPhantomMinSize || v > kPhantomMaxSize) {
            detail::fail(spec, "size " + sizeText + " is out of range (" +
                                   std::to_string(kPhantomMinSize) + ".." +
                                   std::to_string(kPhantomMaxSize) + ")");
        }
        n = int(v);
    }

    const std::vector<std::string> names = phantomNames();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        std::string known;
        for (const std::string& p : names) known += (known.empty() ? "" : ", ") + p;
        detail::fail(spec, "unknown phantom '" + name + "' (known: " + known + ")");
    }
    // The volume cap applies to phantoms too (a 512^3 float phantom is 512 MiB).
    detail::checkedVolumeBytes(spec, "size", n, n, n,
                               name == "shells"      ? VoxelType::UInt8
                               : name == "ct-signed" ? VoxelType::Int16
                                                     : VoxelType::Float32);

    auto centre = [](int i) { return i + 0.5; };
    if (name == "sphere") {
        return floatVolume(spec, n, [&](int i, int j, int k) {
            return spherePhantomValue(n, {centre(i), centre(j), centre(k)});
        });
    }
    if (name == "sphere-over-slab") {
        return floatVolume(spec, n, [&](int i, int j, int k) {
            return sphereOverSlabValue(n, {centre(i), centre(j), centre(k)});
        });
    }
    if (name == "nested-labels") {
        return floatVolume(spec, n, [&](int i, int j, int k) {
            return double(nestedLabelsValue(n, {centre(i), centre(j), centre(k)}));
        });
    }
    if (name == "shells") return makeShells(spec, n);
    if (name == "ct-signed") return makeCtSigned(spec, n);
    if (name == "marschner-lobb") return makeMarschnerLobb(spec, n);
    if (name == "shepp-logan") return makeSheppLogan(spec, n);
    if (name == "ramp-x") return floatVolume(spec, n, [&](int i, int, int) { return centre(i); });
    if (name == "ramp-y") return floatVolume(spec, n, [&](int, int j, int) { return centre(j); });
    return floatVolume(spec, n, [&](int, int, int k) { return centre(k); });  // ramp-z, the last name left
}

}  // namespace voxlab
