// voxlab: the ray profile of one pixel (see ray_profile.h). Plain CPU code in
// double precision, written from the README's rendering conventions; the
// GPU renderers are its test oracle, not its source.
#include "voxlab/ray_profile.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>

#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/renderer.h"
#include "voxlab/renderers.h"
#include "voxlab/transfer_function.h"
#include "ray_profile_scene.h"
#include "volume_reader.h"

namespace voxlab {
namespace {

std::string format(const char* fmt, double a, double b = 0.0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, fmt, a, b);
    return buf;
}

// The gradient in data units per unit length (the smallest spacing), by the
// README's estimators: central differences of the interpolated volume at
// p -+ one spacing along each axis (the two points kept within the range of
// voxel centres, dividing by the distance left), or the 26-neighbour
// version that averages those differences over the 3x3 parallel lines with
// weights [1 2 1] x [1 2 1] / 16. Precomputed gradients are the same
// estimators at the voxels (one-sided at the faces), blended trilinearly.
class GradientReader {
public:
    GradientReader(const VolumeReader& reader, bool sobel, bool precomputed)
        : reader_(reader), sobel_(sobel), precomputed_(precomputed),
          spacing_(reader.volume().spacing()), minSpacing_(reader.volume().minSpacing()) {}

    glm::dvec3 at(const glm::dvec3& p) const {
        if (isCubic(reader_.interpolation()))  // the cubic kernel's own derivative, per voxel -> per unit length
            return glm::dvec3(reader_.cubic(p, 0), reader_.cubic(p, 1), reader_.cubic(p, 2)) / spacing_ * minSpacing_;
        if (precomputed_) return precomputedAt(p);
        glm::dvec3 g(0.0);
        for (int axis = 0; axis < 3; ++axis) {
            if (!sobel_) {
                g[axis] = difference(p, axis);
                continue;
            }
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            double sum = 0.0;
            for (int da = -1; da <= 1; ++da)
                for (int db = -1; db <= 1; ++db) {
                    glm::dvec3 q = p;
                    q[a] += da * spacing_[a];
                    q[b] += db * spacing_[b];
                    sum += (2 - std::abs(da)) * (2 - std::abs(db)) * difference(q, axis);
                }
            g[axis] = sum / 16.0;
        }
        return g * minSpacing_;
    }

private:
    // d f / d x_axis at p, per world unit.
    double difference(const glm::dvec3& p, int axis) const {
        const double h = spacing_[axis];
        const double lowest = 0.5 * h, highest = reader_.extent()[axis] - 0.5 * h;
        glm::dvec3 a = p, b = p;
        a[axis] = std::clamp(p[axis] - h, lowest, highest);
        b[axis] = std::clamp(p[axis] + h, lowest, highest);
        const double distance = b[axis] - a[axis];
        return distance > 0.0 ? (reader_.sample(b) - reader_.sample(a)) / distance : 0.0;
    }

    // The estimator at voxel ijk (inside the grid), per unit length.
    glm::dvec3 atVoxel(glm::ivec3 ijk) const {
        const glm::ivec3 dims = reader_.dims();
        glm::dvec3 g(0.0);
        for (int axis = 0; axis < 3; ++axis) {
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            double sum = 0.0, weights = 0.0;
            for (int da = -1; da <= 1; ++da)
                for (int db = -1; db <= 1; ++db) {
                    if (!sobel_ && (da != 0 || db != 0)) continue;
                    glm::ivec3 line = ijk;
                    line[a] = std::clamp(line[a] + da, 0, dims[a] - 1);
                    line[b] = std::clamp(line[b] + db, 0, dims[b] - 1);
                    glm::ivec3 lo = line, hi = line;
                    lo[axis] = std::max(line[axis] - 1, 0);
                    hi[axis] = std::min(line[axis] + 1, dims[axis] - 1);
                    const double distance = (hi[axis] - lo[axis]) * spacing_[axis];
                    const double d = distance > 0.0 ? (reader_.voxel(hi) - reader_.voxel(lo)) / distance : 0.0;
                    const double weight = (2 - std::abs(da)) * (2 - std::abs(db));
                    sum += weight * d, weights += weight;
                }
            g[axis] = sum / weights;
        }
        return g * minSpacing_;
    }

    glm::dvec3 precomputedAt(const glm::dvec3& p) const {
        const glm::dvec3 u = reader_.voxelCoordinates(p) - 0.5;
        const glm::dvec3 lower = glm::floor(u);
        const glm::dvec3 w = u - lower;
        const glm::ivec3 base(lower);
        glm::dvec3 sum(0.0);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
            const double weight = (o.x ? w.x : 1.0 - w.x) * (o.y ? w.y : 1.0 - w.y) * (o.z ? w.z : 1.0 - w.z);
            sum += weight * atVoxel(glm::clamp(base + o, glm::ivec3(0), reader_.dims() - 1));
        }
        return sum;
    }

    const VolumeReader& reader_;
    bool sobel_, precomputed_;
    glm::dvec3 spacing_;
    double minSpacing_;
};

// Two-sided Phong or Blinn-Phong lighting with a directional light (README,
// "Shading").
struct Lighting {
    bool on = false, blinn = false;
    double ka = 0.2, kd = 0.7, ks = 0.3, shininess = 24.0;
    double minGradient = 0.0;  // data units per unit length
    glm::dvec3 light{0.0};     // towards the light

    Lighting(const ParameterValues& v, const Camera& cam, double valueSpan) {
        auto get = [&](const char* name, double fallback) {
            const auto it = v.find(name);
            return it == v.end() ? fallback : it->second;
        };
        on = get("shading", 0.0) != 0.0;
        blinn = get("blinn", 0.0) != 0.0;
        ka = get("ka", ka), kd = get("kd", kd), ks = get("ks", ks), shininess = get("shininess", shininess);
        minGradient = get("min_gradient", 0.0) * valueSpan;
        // The view direction turned towards the image's right by the azimuth
        // and towards its top (-down) by the elevation.
        const double az = glm::radians(get("light_azimuth", 0.0)), el = glm::radians(get("light_elevation", 0.0));
        light = glm::normalize(-cam.forward * (std::cos(az) * std::cos(el)) +
                               cam.right * (std::sin(az) * std::cos(el)) - cam.down * std::sin(el));
    }

    glm::dvec3 shade(const glm::dvec3& colour, const glm::dvec3& gradient, const glm::dvec3& rayDirection) const {
        if (!on) return colour;
        const double length = glm::length(gradient);
        if (length == 0.0 || length <= minGradient) return colour;  // flat: the normal is noise
        const glm::dvec3 view = -rayDirection;
        glm::dvec3 normal = -gradient / length;
        if (glm::dot(normal, view) < 0.0) normal = -normal;
        const double diffuse = std::max(glm::dot(normal, light), 0.0);
        double specular;
        if (blinn) {
            specular = std::max(glm::dot(normal, glm::normalize(light + view)), 0.0);
        } else {
            const glm::dvec3 reflected = 2.0 * glm::dot(normal, light) * normal - light;  // light mirrored about n
            specular = std::max(glm::dot(reflected, view), 0.0);
        }
        const double highlight = diffuse > 0.0 ? std::pow(specular, shininess) : 0.0;
        return (ka + kd * diffuse) * colour + glm::dvec3(ks * highlight);
    }
};

// The gradient-opacity weight of a gradient magnitude g: 0 at or below low,
// 1 at or above high, linear between; a step at high when high <= low.
double rampWeight(double g, double low, double high) {
    if (high <= low) return g < high ? 0.0 : 1.0;
    return std::clamp((g - low) / (high - low), 0.0, 1.0);
}

// Local ambient occlusion (the ambient_occlusion stage's handout): the mean
// clamped opacity at the 14 points `radius` away from p along the 6 axes and
// the 8 unit diagonals; a point outside the box counts 0.
double localOcclusion(const VolumeReader& reader, const TransferFunction& tf, const glm::dvec3& p, double radius) {
    double sum = 0.0;
    for (int i = 0; i < 14; ++i) {
        glm::dvec3 d(0.0);
        if (i < 6) d[i / 2] = i % 2 == 0 ? 1.0 : -1.0;
        else d = glm::dvec3((i - 6) & 1 ? 1.0 : -1.0, (i - 6) & 2 ? 1.0 : -1.0, (i - 6) & 4 ? 1.0 : -1.0) / std::sqrt(3.0);
        const glm::dvec3 q = p + radius * d;
        if (glm::all(glm::greaterThanEqual(q, glm::dvec3(0.0))) && glm::all(glm::lessThanEqual(q, reader.extent())))
            sum += std::clamp(double(tf.evaluate(reader.sample(q)).a), 0.0, 1.0);
    }
    return sum / 14.0;
}

// The GPU's per-pixel random number for jitter (shaders/voxlab/ray.glsl,
// pixel_random): an integer hash of the fragment's integer coordinates,
// whose rows count from the bottom. A profile must use the very same number
// to land on the same samples.
double pixelRandom(int px, int py, int height) {
    const std::uint32_t x = std::uint32_t(px), y = std::uint32_t(height - 1 - py);
    std::uint32_t h = x * 1973u + y * 9277u + 26699u;
    h = (h ^ (h >> 15)) * 2654435769u;
    h ^= h >> 13;
    h *= 1274126177u;
    h ^= h >> 16;
    return double(h >> 8) / 16777216.0;
}

// How the projection renderers show one value: opaque grey through the
// window, or the transfer function's colour with its opacity. Returns the
// colour and opacity, not premultiplied.
glm::dvec4 displayColour(double value, const glm::dvec2& window, const TransferFunction* tf) {
    if (tf) return glm::dvec4(tf->evaluate(value));
    const double span = window.y - window.x;
    const double grey = span > 0.0 ? std::clamp((value - window.x) / span, 0.0, 1.0) : (value >= window.x ? 1.0 : 0.0);
    return glm::dvec4(grey, grey, grey, 1.0);
}

glm::dvec4 premultiply(const glm::dvec4& c) { return glm::dvec4(glm::dvec3(c) * c.a, c.a); }

// Depth as grey (README, "Depth"): 1 where the ray enters the bounding
// sphere of the box, 0 where it leaves.
double depthGrey(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& extent, double t) {
    const glm::dvec3 centre = 0.5 * extent;
    const double radius = 0.5 * glm::length(extent);
    const double tNear = glm::dot(centre - origin, dir) - radius;
    return std::clamp(1.0 - (t - tNear) / (2.0 * radius), 0.0, 1.0);
}

void addNote(RayProfile& profile, const std::string& text) {
    profile.note += (profile.note.empty() ? "" : "; ") + text;
}

}  // namespace

glm::vec3 profilePixel(const RayProfile& profile, const glm::vec3& background) {
    return glm::vec3(profile.result) + (1.0f - profile.result.a) * background;
}

namespace {

// What the models of the renderers' rays share.
struct ProfileInputs {
    const Volume& volume;
    const Scene& scene;
    const ParameterValues& values;
    const VolumeReader& reader;
    const GradientReader& gradients;
    const Lighting& lighting;
    const TransferFunction* tf;  // the scene's, or compositing's fallback; null: grey through the window
    glm::dvec2 window;
    const ProfileSceneClassifier* sceneClassifier;  // a label map or a fused volume; null: neither

    double param(const char* name) const { return values.at(name); }
    bool on(const char* name) const {
        const auto it = values.find(name);
        return it != values.end() && it->second != 0.0;
    }
};

void freeze(RayProfile& profile, int from, const glm::vec4& accumulated) {
    for (std::size_t k = std::size_t(from); k < profile.samples.size(); ++k) profile.samples[k].accumulated = accumulated;
}

// Clips a ray to the box cropped by the roi (an roi that misses the box
// leaves nothing) and by the clip planes' half-spaces.
bool clipToSceneRegion(const Volume& volume, const Scene& scene, const glm::dvec3& origin, const glm::dvec3& dir,
                       double* t0, double* t1) {
    glm::dvec3 lo(0.0), hi = volume.extent();
    if (scene.roi) {
        lo = glm::max(lo, scene.roi->min * volume.spacing());
        hi = glm::min(hi, scene.roi->max * volume.spacing());
        if (lo.x >= hi.x || lo.y >= hi.y || lo.z >= hi.z) return false;
    }
    bool hits = clipRayToBox(origin, dir, lo, hi, t0, t1);
    for (const ClipPlane& plane : scene.clipPlanes)
        hits = hits && clipToHalfSpace(origin, dir, plane.point * volume.spacing(), glm::normalize(plane.normal), t0, t1);
    return hits;
}

// The ray through the pixel's centre, clipped to the box cropped by the roi
// (an roi that misses the box leaves nothing), the cutting plane's
// half-space and the renderer's own clipping. Returns whether any is left.
bool clipPixelRay(RayProfile& profile, const Renderer& renderer, const Volume& volume, const Scene& scene,
                  const ParameterValues& values, const Camera& cam) {
    cam.ray(profile.px + 0.5, profile.py + 0.5, &profile.origin, &profile.direction);
    const glm::dvec3 origin = profile.origin, dir = profile.direction;
    double t0 = 0.0, t1 = 0.0;
    bool hits = clipToSceneRegion(volume, scene, origin, dir, &t0, &t1);
    if (hits && scene.cuttingPlane) {
        const CuttingPlane& cut = *scene.cuttingPlane;
        const glm::dvec3 point = cut.point.value_or(glm::dvec3(volume.dims()) * 0.5) * volume.spacing();
        hits = clipToHalfSpace(origin, dir, point, glm::normalize(cut.normal), &t0, &t1);
        if (cut.otherRenderer != "none")
            addNote(profile, "cutting plane: only " + profile.renderer + "'s half-space is followed, not " +
                                 cut.otherRenderer + "'s");
    }
    if (hits) hits = renderer.clipProfileRay(volume, cam.forward, values, origin, dir, &t0, &t1);
    if (!hits) return false;
    const auto jitter = values.find("jitter");
    if (jitter != values.end() && jitter->second != 0.0)
        t0 += (pixelRandom(profile.px, profile.py, scene.height) - 0.5) * profile.step;  // the GPU's start
    profile.tEntry = t0, profile.tExit = t1;
    return true;
}

// The samples: floor(length / step + 1/2) of them, at t_entry + (m + 1/2) step.
void takeSamples(RayProfile& profile, const VolumeReader& reader) {
    const double t0 = profile.tEntry, t1 = profile.tExit;
    const int count = std::max(0, int(std::floor((t1 - t0) / profile.step + 0.5)));
    profile.samples.resize(std::size_t(count));
    double maximum = -std::numeric_limits<double>::infinity(), minimum = -maximum, sum = 0.0;
    for (int m = 0; m < count; ++m) {
        RaySample& s = profile.samples[std::size_t(m)];
        s.t = t0 + (m + 0.5) * profile.step;
        s.position = profile.origin + s.t * profile.direction;
        s.value = reader.sample(s.position);
        maximum = std::max(maximum, s.value), minimum = std::min(minimum, s.value), sum += s.value;
        s.runningMax = maximum, s.runningMin = minimum, s.runningMean = sum / (m + 1);
    }
}

// Pre-classification: the 8 voxels around p classified, their
// opacity-weighted colours blended (nearest: the one voxel).
glm::dvec4 classifyPre(const ProfileInputs& in, const glm::dvec3& p) {
    auto classifyVoxel = [&](glm::ivec3 ijk) { return glm::dvec4(in.tf->evaluate(in.reader.voxel(ijk))); };
    if (in.scene.interpolation == Interpolation::Nearest)
        return classifyVoxel(glm::ivec3(glm::floor(in.reader.voxelCoordinates(p))));
    const glm::dvec3 u = in.reader.voxelCoordinates(p) - 0.5;
    const glm::dvec3 lower = glm::floor(u), w = u - lower;
    glm::dvec4 acc(0.0);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        const double weight = (o.x ? w.x : 1.0 - w.x) * (o.y ? w.y : 1.0 - w.y) * (o.z ? w.z : 1.0 - w.z);
        acc += weight * premultiply(classifyVoxel(glm::ivec3(lower) + o));
    }
    return acc.a > 0.0 ? glm::dvec4(glm::dvec3(acc) / acc.a, acc.a) : glm::dvec4(0.0);
}

// Pre-integration (the preintegration stage's handout): the segment from
// `front` to `back`, `length` unit lengths, integrated in double with 1024
// pieces (the GPU reads a 256x256 table of fewer). Returns its colour (not
// premultiplied) and its opacity per unit length, as the stage hands them
// to the compositing loop.
glm::dvec4 preintegratedSegment(const TransferFunction& tf, double front, double back, double length) {
    constexpr int kPieces = 1024;
    glm::dvec3 colour(0.0);
    double opacity = 0.0;
    for (int k = 0; k < kPieces; ++k) {
        const glm::dvec4 c(tf.evaluate(front + (back - front) * (k + 0.5) / kPieces));
        const double a = 1.0 - std::pow(1.0 - std::clamp(c.a, 0.0, 1.0), length / kPieces);
        colour += (1.0 - opacity) * a * glm::dvec3(c);
        opacity += (1.0 - opacity) * a;
    }
    if (opacity <= 0.0) return glm::dvec4(0.0);
    return {colour / opacity, 1.0 - std::pow(std::max(1.0 - opacity, 0.0), 1.0 / length)};
}

// Shadows (the shadows stage's handout): the transmittance along the shadow
// ray from p, sampled every light-volume voxel, starting one such voxel
// towards the light as composite.frag reads the light volume. The GPU
// interpolates a light volume of these; here the ray is followed itself.
double shadowTransmittance(const ProfileInputs& in, const glm::dvec3& p) {
    const glm::ivec3 size = lightVolumeSize(in.volume.dims(), int(in.param("shadow_resolution")));
    const glm::dvec3 texel = in.volume.extent() / glm::dvec3(size);
    const double step = std::min({texel.x, texel.y, texel.z});
    const glm::dvec3 light = in.lighting.light, start = p + step * light;
    double transmittance = 1.0;
    for (int k = 1; transmittance > 1e-3; ++k) {
        const glm::dvec3 q = start + double(k) * step * light;
        if (glm::any(glm::lessThan(q, glm::dvec3(0.0))) || glm::any(glm::greaterThan(q, in.volume.extent()))) break;
        const double alpha = std::clamp(double(in.tf->evaluate(in.reader.sample(q)).a), 0.0, 1.0);
        transmittance *= std::pow(1.0 - alpha, step / in.volume.minSpacing());
    }
    return transmittance;
}

// One sample of the composite renderer, as composite.frag makes it: its
// colour (rgb, lit) and opacity per unit length.
glm::dvec4 compositeSample(const ProfileInputs& in, const RaySample& s, const glm::dvec3& dir, double step) {
    glm::dvec4 c;
    if (in.sceneClassifier)
        c = in.sceneClassifier->classify(s.position, s.value);
    else if (in.on("preintegrated"))
        c = preintegratedSegment(*in.tf, s.value, in.reader.sample(s.position + step * dir), in.scene.step);
    else
        c = in.on("preclassify") ? classifyPre(in, s.position) : glm::dvec4(in.tf->evaluate(s.value));
    if (c.a > 0.0 && in.on("gradient_opacity"))  // the gradient_opacity stage's ramp (its handout)
        c.a *= rampWeight(glm::length(in.gradients.at(s.position)), in.param("gradient_low"), in.param("gradient_high"));
    if (c.a > 0.0 && in.lighting.on)
        c = glm::dvec4(in.lighting.shade(glm::dvec3(c), in.gradients.at(s.position), dir), c.a);
    if (c.a > 0.0 && in.on("shadows")) c = glm::dvec4(glm::dvec3(c) * shadowTransmittance(in, s.position), c.a);
    if (c.a > 0.0 && in.on("ambient_occlusion")) {  // the ambient_occlusion stage (its handout)
        const double o = localOcclusion(in.reader, *in.tf, s.position, in.param("ao_radius") * in.volume.minSpacing());
        c = glm::dvec4(glm::dvec3(c) * (1.0 - in.param("ao_strength") * o), c.a);
    }
    return c;
}

void profileComposite(RayProfile& profile, const ProfileInputs& in) {
    const bool backToFront = in.on("back_to_front");
    profile.earlyTermination = backToFront ? 1.0 : in.param("early_termination");
    glm::dvec3 colour(0.0);
    double opacity = 0.0;
    for (std::size_t m = 0; m < profile.samples.size(); ++m) {
        RaySample& s = profile.samples[m];
        const glm::dvec4 c = compositeSample(in, s, profile.direction, profile.step);
        // Opacity per unit length, corrected for a step of stepUnits units.
        const double a = 1.0 - std::pow(1.0 - std::clamp(c.a, 0.0, 1.0), in.scene.step);
        s.classified = glm::vec4(glm::vec3(c), float(a));
        if (profile.stoppedAt >= 0) continue;  // past the stop: classified, not composited
        colour += (1.0 - opacity) * a * glm::dvec3(c);
        opacity += (1.0 - opacity) * a;
        s.accumulated = glm::vec4(glm::vec3(colour), float(opacity));
        if (!backToFront && opacity >= profile.earlyTermination) {
            profile.stoppedAt = int(m);
            profile.why = format("early ray termination: accumulated opacity %.3f >= %g", opacity, profile.earlyTermination);
            freeze(profile, int(m) + 1, s.accumulated);
        }
    }
    profile.result = glm::vec4(glm::vec3(colour), float(opacity));
    if (profile.stoppedAt < 0)
        profile.why = backToFront ? "the ray left the volume (back to front: no early termination)" : "the ray left the volume";
    if (in.lighting.on && in.on("precomputed_gradients"))
        addNote(profile, "precomputed gradients blended in double (the GPU filters a float texture)");
    if (in.on("preintegrated"))
        addNote(profile, "pre-integrated segments integrated in double (the GPU interpolates a 256x256 table)");
    if (in.on("shadows"))
        addNote(profile, "shadows: each sample's shadow ray followed itself (the GPU interpolates a light volume)");
}

// mip, slab_mip, minip, average: the running maximum, minimum or mean.
void profileProjection(RayProfile& profile, const ProfileInputs& in) {
    const bool isMin = profile.model == ProfileModel::Minimum, isMean = profile.model == ProfileModel::Mean;
    for (std::size_t m = 0; m < profile.samples.size(); ++m) {
        RaySample& s = profile.samples[m];
        s.accumulated = glm::vec4(premultiply(displayColour(isMean ? s.runningMean : isMin ? s.runningMin : s.runningMax,
                                                            in.window, in.tf)));
        const double extreme = isMin ? s.runningMin : s.runningMax;
        const bool newExtreme = profile.chosen < 0 || extreme != profile.samples[std::size_t(profile.chosen)].value;
        if (!isMean && s.value == extreme && newExtreme) profile.chosen = int(m);  // the first to reach it
    }
    if (profile.samples.empty()) {
        profile.why = "the ray crosses less than half a step of the volume: no sample";
        return;
    }
    profile.result = profile.samples.back().accumulated;
    profile.why = "the ray left the volume";
}

void profileFirstHit(RayProfile& profile, const ProfileInputs& in) {
    profile.threshold = in.param("threshold"), profile.hasThreshold = true;
    for (std::size_t m = 0; m < profile.samples.size() && profile.stoppedAt < 0; ++m) {
        const RaySample& s = profile.samples[m];
        if (s.value < profile.threshold) continue;
        profile.stoppedAt = profile.chosen = int(m);
        profile.hitT = s.t;
        profile.why = format("first hit: value %g >= threshold %g", s.value, profile.threshold);
        const double grey = depthGrey(profile.origin, profile.direction, in.volume.extent(), s.t);
        profile.result = in.on("depth") ? glm::vec4(glm::vec3(float(grey)), 1.0f)
                                        : glm::vec4(premultiply(displayColour(s.value, in.window, in.tf)));
        freeze(profile, int(m), profile.result);
    }
    if (profile.stoppedAt < 0)
        profile.why = format("the ray left the volume (no sample reached threshold %g)", profile.threshold);
}

// iso: value - isovalue changes sign between two samples (a value equal to
// the isovalue counts as above); bisection narrows the interval.
void profileIsosurface(RayProfile& profile, const ProfileInputs& in) {
    profile.threshold = in.param("isovalue"), profile.hasThreshold = true;
    const double iso = profile.threshold;
    const int refinements = int(in.param("refinement_steps"));
    const glm::dvec3 origin = profile.origin, dir = profile.direction;
    for (std::size_t m = 0; m < profile.samples.size() && profile.stoppedAt < 0; ++m) {
        const RaySample& s = profile.samples[m];
        const bool above = s.value - iso >= 0.0;
        if (m == 0 && above) {
            profile.hitT = s.t;
            profile.why = format("the ray starts inside the surface: sample 0 has value %g >= isovalue %g", s.value, iso);
        } else if (m > 0 && (profile.samples[m - 1].value - iso >= 0.0) != above) {
            double tLo = profile.samples[m - 1].t, tHi = s.t;
            const bool loAbove = !above;
            for (int k = 0; k < refinements; ++k) {
                const double mid = 0.5 * (tLo + tHi);
                if ((in.reader.sample(origin + mid * dir) - iso >= 0.0) == loAbove) tLo = mid;
                else tHi = mid;
            }
            profile.hitT = refinements > 0 ? 0.5 * (tLo + tHi) : s.t;
            profile.why = "isovalue crossed between samples " + std::to_string(m - 1) + " and " + std::to_string(m);
        } else {
            continue;
        }
        profile.stoppedAt = profile.chosen = int(m);
        glm::dvec3 colour(in.param("color_r"), in.param("color_g"), in.param("color_b"));
        if (in.on("depth")) colour = glm::dvec3(depthGrey(origin, dir, in.volume.extent(), profile.hitT));
        else if (in.lighting.on) colour = in.lighting.shade(colour, in.gradients.at(origin + profile.hitT * dir), dir);
        profile.result = glm::vec4(glm::vec3(colour), 1.0f);
        freeze(profile, int(m), profile.result);
    }
    if (profile.stoppedAt < 0) profile.why = format("the ray left the volume (the isovalue %g is never crossed)", iso);
}

}  // namespace

RayProfile computeRayProfile(const Volume& volume, const Scene& scene, int px, int py) {
    if (px < 0 || py < 0 || px >= scene.width || py >= scene.height)
        throw Error("ray profile: pixel (" + std::to_string(px) + ", " + std::to_string(py) + ") is outside the " +
                    std::to_string(scene.width) + "x" + std::to_string(scene.height) + " image");
    const Renderer& renderer = rendererRegistry().get(scene.renderer);
    const ParameterValues values = renderer.resolveParameters(scene.parameters, volume.valueRange());

    RayProfile profile;
    profile.px = px, profile.py = py;
    profile.renderer = renderer.id();
    profile.stepUnits = scene.step;
    profile.step = scene.step * volume.minSpacing();
    profile.model = renderer.profileModel();
    const bool modelled = profile.model != ProfileModel::None;
    const Camera cam = Camera::make(scene.camera, volume.extent(), scene.width, scene.height);
    profile.hitsVolume = clipPixelRay(profile, renderer, volume, scene, values, cam);
    if (!profile.hitsVolume) {
        profile.why = "the ray misses the volume";
        profile.modelled = modelled;
        return profile;
    }
    const VolumeReader reader(volume, scene.interpolation);
    if (scene.interpolation == Interpolation::Hardware)
        addNote(profile, "hardware interpolation read as trilinear (the GPU may blend with 8-bit weights)");
    takeSamples(profile, reader);
    if (!modelled) {
        profile.why = "not modelled for " + profile.renderer;
        return profile;
    }
    profile.modelled = true;

    const glm::dvec2 window = scene.window.value_or(volume.valueRange());
    const glm::dvec2 range = volume.valueRange();
    // The transfer function the renderer classifies with: the scene's, or
    // for compositing without one the engine's fallback, a white ramp over
    // the window from opacity 0 to 0.1 per unit length (render_engine.h).
    std::optional<TransferFunction> tf = scene.transferFunction;
    if (!tf && renderer.needsTransferFunction()) tf = defaultCompositingFunction(window);
    const Lighting lighting(values, cam, range.y - range.x);
    auto flag = [&](const char* name) {
        const auto it = values.find(name);
        return it != values.end() && it->second != 0.0;
    };
    const GradientReader gradients(reader, flag("sobel"), flag("precomputed_gradients"));
    // A label map or a second volume replaces the classification (composite).
    const std::unique_ptr<ProfileSceneClassifier> sceneClassifier =
        profile.model == ProfileModel::Composite && tf ? ProfileSceneClassifier::make(scene, volume, *tf) : nullptr;
    const ProfileInputs in{volume, scene, values, reader, gradients, lighting, tf ? &*tf : nullptr, window,
                           sceneClassifier.get()};

    switch (profile.model) {
        case ProfileModel::Composite: profileComposite(profile, in); break;
        case ProfileModel::FirstHit: profileFirstHit(profile, in); break;
        case ProfileModel::Isosurface: profileIsosurface(profile, in); break;
        default:  // Maximum, Minimum, Mean
            for (RaySample& s : profile.samples) s.classified = glm::vec4(displayColour(s.value, window, in.tf));
            profileProjection(profile, in);
    }
    return profile;
}

double samplesByRule(const Volume& volume, const Scene& scene) {
    const Camera camera = Camera::make(scene.camera, volume.extent(), scene.width, scene.height);
    const double step = scene.step * volume.minSpacing();
    double total = 0.0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            glm::dvec3 o, d;
            camera.ray(x + 0.5, y + 0.5, &o, &d);
            double t0 = 0.0, t1 = 0.0;
            if (clipToSceneRegion(volume, scene, o, d, &t0, &t1)) total += std::floor((t1 - t0) / step + 0.5);
        }
    return total;
}

}  // namespace voxlab
