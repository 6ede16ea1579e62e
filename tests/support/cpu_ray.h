// Test support: a camera ray composited on the CPU from the README's
// conventions, written for the tests (not from ray.glsl or composite.glsl):
//  - the ray is clipped to the box [0, extent] (slab method, never behind
//    its origin), then to each kept half-space dot(p - point, normal) >= 0;
//  - sample m sits at t_entry + (m + 1/2) step while t < t_exit;
//  - a sample's classification (colour, opacity per unit length) is
//    corrected to a = 1 - (1 - alpha)^step_units and composited front to
//    back, stopping once the opacity reaches `earlyTermination`.
// The classification is the test's own: a callback from world position to
// (rgb, alpha), so each test states what it expects a sample to be.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/camera.h"
#include "voxlab/transfer_function.h"
#include "cpu_tf.h"

namespace voxlab::testing {

struct HalfSpace {
    glm::dvec3 point, normal;  // world units; normal of any length
};

// [*t0, *t1] of the ray inside the box and the half-spaces; false if empty.
inline bool cpuClipRay(glm::dvec3 o, glm::dvec3 d, glm::dvec3 extent, const std::vector<HalfSpace>& keep,
                       double* t0, double* t1) {
    double lo = 0.0, hi = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < 0.0 || o[a] > extent[a]) return false;
            continue;
        }
        const double ta = -o[a] / d[a], tb = (extent[a] - o[a]) / d[a];
        lo = std::max(lo, std::min(ta, tb)), hi = std::min(hi, std::max(ta, tb));
    }
    for (const HalfSpace& h : keep) {
        const double along = glm::dot(d, h.normal), start = glm::dot(o - h.point, h.normal);
        if (along == 0.0) {
            if (start < 0.0) return false;
            continue;
        }
        const double t = -start / along;
        if (along > 0.0) lo = std::max(lo, t);
        else hi = std::min(hi, t);
    }
    *t0 = lo, *t1 = hi;
    return hi > lo;
}

// The premultiplied colour and opacity of one pixel's ray.
using Classifier = std::function<glm::dvec4(glm::dvec3)>;
inline glm::dvec4 cpuCompositeRay(glm::dvec3 o, glm::dvec3 d, glm::dvec3 extent, const std::vector<HalfSpace>& keep,
                                  double step, double stepUnits, double earlyTermination,
                                  const Classifier& classify) {
    double t0 = 0.0, t1 = 0.0;
    if (!cpuClipRay(o, d, extent, keep, &t0, &t1)) return glm::dvec4(0.0);
    const int count = int(std::floor((t1 - t0) / step + 0.5));
    glm::dvec3 colour(0.0);
    double opacity = 0.0;
    for (int m = 0; m < count; ++m) {
        const glm::dvec4 c = classify(o + (t0 + (m + 0.5) * step) * d);
        const double a = 1.0 - std::pow(1.0 - std::clamp(c.a, 0.0, 1.0), stepUnits);
        colour += (1.0 - opacity) * a * glm::dvec3(c);
        opacity += (1.0 - opacity) * a;
        if (opacity >= earlyTermination) break;
    }
    return {colour, opacity};
}

}  // namespace voxlab::testing
