// Test support: the piecewise-linear transfer function, written for the
// tests as an oracle: colour and alpha interpolated linearly between the
// control points (sorted by value), clamped to the end points outside them
// (below the first, or NaN: the first; no points: transparent black).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "voxlab/transfer_function.h"

namespace voxlab::testing {

inline glm::dvec4 cpuTransferFunction(const std::vector<ControlPoint>& pts, double v) {
    const auto rgba = [](const ControlPoint& p) { return glm::dvec4(glm::dvec3(p.color), double(p.alpha)); };
    if (pts.empty()) return glm::dvec4(0.0);
    if (!(v >= pts.front().value)) return rgba(pts.front());
    if (v >= pts.back().value) return rgba(pts.back());
    for (std::size_t i = 1; i < pts.size(); ++i)
        if (v < pts[i].value) {
            const double t = (v - pts[i - 1].value) / (pts[i].value - pts[i - 1].value);
            return rgba(pts[i - 1]) + t * (rgba(pts[i]) - rgba(pts[i - 1]));
        }
    return rgba(pts.back());
}

}  // namespace voxlab::testing
