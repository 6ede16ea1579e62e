// voxlab: the ray profile of one pixel, read from the renderer's own shaders
// (see ray_profile.h; the instrumented run is RenderEngine::profileRay in
// render_engine_profile.cpp and shaders/voxlab/profile.glsl). This file
// turns what the run read back into the profile: it computes nothing of
// the technique itself.
#include "voxlab/ray_profile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "voxlab/camera.h"

namespace voxlab {
namespace {

std::string format(const char* fmt, double a, double b = 0.0) {
    char text[200];
    std::snprintf(text, sizeof text, fmt, a, b);
    return text;
}

void addNote(RayProfile& profile, const std::string& text) {
    profile.note += (profile.note.empty() ? "" : "; ") + text;
}

// How one value alone is shown (the strips of the projection renderers):
// opaque grey through the window, or the transfer function's colour with
// its opacity, not premultiplied.
glm::vec4 displayColour(double value, const glm::dvec2& window, const TransferFunction* tf) {
    if (tf) return tf->evaluate(value);
    const double span = window.y - window.x;
    const double grey = span > 0.0 ? std::clamp((value - window.x) / span, 0.0, 1.0) : (value >= window.x ? 1.0 : 0.0);
    return glm::vec4(glm::vec3(float(grey)), 1.0f);
}

// The last sample whose pixel differs from the one before it: after it the
// stage's loop took nothing more (or took only what added nothing).
int lastChange(const std::vector<glm::vec4>& pixels) {
    int last = pixels.empty() ? -1 : 0;
    for (std::size_t i = 1; i < pixels.size(); ++i)
        if (pixels[i] != pixels[i - 1]) last = int(i);
    return last;
}

// Compositing: sample i's colour and opacity, as the stage applied them,
// from the pixel after i - 1 and after i: front to back,
// A_i = A_{i-1} + (1 - A_{i-1}) a_i and C_i = C_{i-1} + (1 - A_{i-1}) a_i c_i.
void deriveComposite(RayProfile& profile, const ProfileReadings& in) {
    glm::vec4 before(0.0f);
    for (std::size_t i = 0; i < profile.samples.size(); ++i) {
        RaySample& s = profile.samples[i];
        const float room = 1.0f - before.a;
        const float a = room > 1e-6f ? std::clamp((s.accumulated.a - before.a) / room, 0.0f, 1.0f) : 0.0f;
        const glm::vec3 c = a > 1e-6f ? (glm::vec3(s.accumulated) - glm::vec3(before)) / (room * a) : glm::vec3(0.0f);
        s.classified = glm::vec4(glm::clamp(c, 0.0f, 1.0f), a);
        before = s.accumulated;
    }
    const int last = lastChange(in.accumulated);
    profile.earlyTermination = in.earlyTermination;
    // (At 1 there is no early termination: back to front, or switched off.)
    if (in.earlyTermination < 1.0 && last >= 0 && last + 1 < in.samples &&
        profile.result.a >= in.earlyTermination - 1e-4) {
        profile.stoppedAt = last;
        profile.why = format("early ray termination: accumulated opacity %.3f >= %g", profile.result.a, in.earlyTermination);
    } else {
        profile.why = "the ray left the volume";
    }
}

// MIP, MinIP, the mean: the value the entry shader displayed after each
// sample (its running maximum, minimum or mean).
void deriveProjection(RayProfile& profile, const ProfileReadings& in) {
    const bool isMin = profile.model == ProfileModel::Minimum, isMean = profile.model == ProfileModel::Mean;
    for (std::size_t i = 0; i < profile.samples.size(); ++i) {
        RaySample& s = profile.samples[i];
        const double shown = in.records[i].y;
        (isMean ? s.runningMean : isMin ? s.runningMin : s.runningMax) = shown;
        s.classified = displayColour(s.value, in.window, in.tf);
        if (!isMean && (i == 0 || shown != in.records[i - 1].y)) profile.chosen = int(i);  // where it last changed
    }
    profile.why = "the ray left the volume";
}

// First hit and isosurface: the first sample after which the pixel is no
// longer empty.
void deriveHit(RayProfile& profile, const ProfileReadings& in) {
    profile.threshold = in.threshold, profile.hasThreshold = true;
    for (std::size_t i = 0; i < profile.samples.size(); ++i)
        if (profile.samples[i].accumulated.a > 0.0f) {
            profile.stoppedAt = profile.chosen = int(i);
            profile.hitT = profile.samples[i].t;
            profile.why = profile.model == ProfileModel::Isosurface
                              ? "isovalue crossed by sample " + std::to_string(i) + " (the hit lies before it)"
                              : format("first hit at sample %g (threshold %g)", double(i), in.threshold);
            return;
        }
    profile.why = "the ray left the volume without a hit (" +
                  std::string(profile.model == ProfileModel::Isosurface ? "isovalue " : "threshold ") +
                  format("%g", in.threshold) + ")";
}

}  // namespace

glm::vec3 profilePixel(const RayProfile& profile, const glm::vec3& background) {
    return glm::vec3(profile.result) + (1.0f - profile.result.a) * background;
}

void fillRayProfile(RayProfile& profile, const ProfileReadings& in) {
    profile.modelled = true;
    profile.result = in.result;
    if (in.samples == kProfileStub) {
        profile.why = "a stage it needs is not implemented yet: its stub was reached";
        return;
    }
    if (in.samples == kProfileNoSamples) {
        profile.hitsVolume = true;
        profile.why = profile.renderer + "'s shader takes no samples through sample_count(): nothing to follow";
        return;
    }
    profile.hitsVolume = in.samples >= 0;
    if (!profile.hitsVolume) {
        profile.why = "the ray misses the volume";
        return;
    }
    const std::size_t taken = std::min(in.accumulated.size(), in.records.size());
    if (taken < std::size_t(in.samples))
        addNote(profile, format("the first %g of the ray's %g samples", double(taken), double(in.samples)));
    profile.samples.resize(taken);
    double sum = 0.0;
    for (std::size_t i = 0; i < taken; ++i) {
        RaySample& s = profile.samples[i];
        s.t = in.records[i].z;
        s.position = profile.origin + s.t * profile.direction;
        s.value = in.records[i].x;
        s.accumulated = in.accumulated[i];
        // The values' running statistics, for the plot; a projection
        // renderer's own (what its shader displayed) replace them below.
        sum += s.value;
        s.runningMax = i ? std::max(profile.samples[i - 1].runningMax, s.value) : s.value;
        s.runningMin = i ? std::min(profile.samples[i - 1].runningMin, s.value) : s.value;
        s.runningMean = sum / double(i + 1);
    }
    profile.tEntry = taken ? profile.samples[0].t - 0.5 * profile.step : 0.0;
    profile.tExit = profile.tEntry + in.samples * profile.step;
    if (in.samples == 0) {
        profile.why = "the ray crosses less than half a step of the volume: no sample";
        return;
    }
    switch (profile.model) {
        case ProfileModel::Composite: deriveComposite(profile, in); break;
        case ProfileModel::Maximum:
        case ProfileModel::Minimum:
        case ProfileModel::Mean: deriveProjection(profile, in); break;
        case ProfileModel::FirstHit:
        case ProfileModel::Isosurface: deriveHit(profile, in); break;
        case ProfileModel::None: profile.why = "the ray left the volume"; break;
    }
}

double samplesByRule(const Volume& volume, const Scene& scene) {
    const Camera camera = Camera::make(scene.camera, volume.extent(), scene.width, scene.height);
    const double step = scene.step * volume.minSpacing();
    glm::dvec3 lo(0.0), hi = volume.extent();
    if (scene.roi) {
        lo = glm::max(lo, scene.roi->min * volume.spacing());
        hi = glm::min(hi, scene.roi->max * volume.spacing());
        if (lo.x >= hi.x || lo.y >= hi.y || lo.z >= hi.z) return 0.0;  // an roi that misses the box
    }
    double total = 0.0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            glm::dvec3 o, d;
            camera.ray(x + 0.5, y + 0.5, &o, &d);
            double t0 = 0.0, t1 = 0.0;
            bool hits = clipRayToBox(o, d, lo, hi, &t0, &t1);
            for (const ClipPlane& plane : scene.clipPlanes)
                hits = hits && clipToHalfSpace(o, d, plane.point * volume.spacing(), glm::normalize(plane.normal), &t0, &t1);
            if (hits) total += std::floor((t1 - t0) / step + 0.5);
        }
    return total;
}

}  // namespace voxlab
