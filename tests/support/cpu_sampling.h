// Test support: the README's sampling rules on the CPU, in double, written
// from the conventions (not from sampling.glsl, gradient.glsl or
// gradients.cpp): the oracle that the sampling, gradient and empty-space
// tests hold the GPU to.
//  - Voxel (i, j, k) is centred at ((i, j, k) + 1/2) * spacing; outside the
//    grid the border voxel continues (clamp-to-edge).
//  - Trilinear interpolation blends the 8 voxel centres around a point.
//  - The gradient stage's central difference along axis a differences the
//    interpolated field at p -+ spacing_a e_a, both clamped into the range of
//    voxel centres, over the distance left between them; gradients are in
//    data units per smallest spacing.
#pragma once

#include <algorithm>
#include <cstdlib>

#include <glm/glm.hpp>

#include "voxlab/volume.h"

namespace voxlab::testing {

// Voxel ijk's value, indices clamped to the grid.
inline double clampedVoxel(const Volume& v, glm::ivec3 ijk) {
    ijk = glm::clamp(ijk, glm::ivec3(0), v.dims() - 1);
    return v.value(ijk.x, ijk.y, ijk.z);
}

// Trilinear interpolation at world point p. With centres at i + 1/2, u - 1/2
// puts them on integers; the lower corner is its floor and the fractional
// part weighs the upper neighbour on each axis.
inline double cpuTrilinear(const Volume& v, glm::dvec3 p) {
    const glm::dvec3 u = p / v.spacing() - 0.5;
    const glm::dvec3 lower = glm::floor(u), w = u - lower;
    double sum = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        const double weight = (o.x ? w.x : 1.0 - w.x) * (o.y ? w.y : 1.0 - w.y) * (o.z ? w.z : 1.0 - w.z);
        sum += weight * clampedVoxel(v, glm::ivec3(lower) + o);
    }
    return sum;
}

// Nearest-neighbour sampling at world point p: the voxel whose cell holds it.
inline double cpuNearest(const Volume& v, glm::dvec3 p) {
    return clampedVoxel(v, glm::ivec3(glm::floor(p / v.spacing())));
}

// d f / d(world) along `axis` at world point p, by the central difference
// of the interpolated field (see above); 0 on a one-voxel axis. With
// `nearest`, of the nearest-neighbour field instead.
inline double cpuLineDerivative(const Volume& v, glm::dvec3 p, int axis, bool nearest = false) {
    const double h = v.spacing()[axis];
    glm::dvec3 lo = p, hi = p;
    lo[axis] = std::clamp(p[axis] - h, 0.5 * h, v.extent()[axis] - 0.5 * h);
    hi[axis] = std::clamp(p[axis] + h, 0.5 * h, v.extent()[axis] - 0.5 * h);
    if (hi[axis] <= lo[axis]) return 0.0;
    const auto f = [&](glm::dvec3 q) { return nearest ? cpuNearest(v, q) : cpuTrilinear(v, q); };
    return (f(hi) - f(lo)) / (hi[axis] - lo[axis]);
}

// The gradient stage's central differences at world point p, in data units
// per smallest spacing.
inline glm::dvec3 cpuCentralGradient(const Volume& v, glm::dvec3 p) {
    return glm::dvec3(cpuLineDerivative(v, p, 0), cpuLineDerivative(v, p, 1), cpuLineDerivative(v, p, 2)) *
           v.minSpacing();
}

// The 26-neighbour estimator: along each axis a, the central differences
// at the 3x3 positions p + da spacing_b e_b + db spacing_c e_c around it
// (b, c the other two axes), weighed (2 - |da|)(2 - |db|) / 16, in data
// units per smallest spacing.
inline glm::dvec3 cpuSobelGradient(const Volume& v, glm::dvec3 p) {
    glm::dvec3 g(0.0);
    for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int da = -1; da <= 1; ++da)
            for (int db = -1; db <= 1; ++db) {
                glm::dvec3 q = p;
                q[b] += da * v.spacing()[b];
                q[c] += db * v.spacing()[c];
                g[a] += (2 - std::abs(da)) * (2 - std::abs(db)) / 16.0 * cpuLineDerivative(v, q, a);
            }
    }
    return g * v.minSpacing();
}

}  // namespace voxlab::testing
