// voxlab internals: reading a volume between voxels on the CPU, in double,
// as the README's conventions say (the ray profile and its scene classifier).
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "voxlab/bspline.h"
#include "voxlab/scene.h"
#include "voxlab/volume.h"

namespace voxlab {

// Reading the volume between voxels: continuous voxel coordinates put voxel
// i's cell at [i, i+1], so its centre is at i + 1/2; indices are clamped to
// the grid (the border value continues outwards).
// The cubic interpolations read the kernels of the cubic stage's handout
// (reference/cubic/README.md), the B-spline on coefficients (bspline.h)
// that the reader computes once.
class VolumeReader {
public:
    VolumeReader(const Volume& volume, Interpolation interpolation)
        : volume_(volume), dims_(volume.dims()), extent_(volume.extent()), interpolation_(interpolation) {
        if (interpolation == Interpolation::BSpline) coefficients_ = bsplineCoefficients(volume);
    }

    double voxel(glm::ivec3 ijk) const {
        ijk = glm::clamp(ijk, glm::ivec3(0), dims_ - 1);
        return volume_.value(ijk.x, ijk.y, ijk.z);
    }
    glm::dvec3 voxelCoordinates(const glm::dvec3& p) const { return p / extent_ * glm::dvec3(dims_); }

    double sample(const glm::dvec3& p) const {
        if (interpolation_ == Interpolation::Nearest) return voxel(glm::ivec3(glm::floor(voxelCoordinates(p))));
        if (isCubic(interpolation_)) return cubic(p, -1);
        return trilinear(p);  // "hardware" too: the GPU's filter, without its reduced-precision weights
    }

    // The cubic reconstruction at p, or its derivative along `axis` (per
    // voxel) when axis is 0, 1 or 2.
    double cubic(const glm::dvec3& p, int axis) const {
        const glm::dvec3 u = voxelCoordinates(p) - 0.5, lower = glm::floor(u), t = u - lower;
        const glm::ivec3 base = glm::ivec3(lower) - 1;
        double w[3][4];
        for (int k = 0; k < 3; ++k) weights(t[k], k == axis, w[k]);
        double sum = 0.0;
        for (int c = 0; c < 4; ++c)
            for (int b = 0; b < 4; ++b)
                for (int a = 0; a < 4; ++a) sum += w[0][a] * w[1][b] * w[2][c] * tap(base + glm::ivec3(a, b, c));
        return sum;
    }

    // Shifted by -1/2 the voxel centres sit on integers: the lower corner is
    // floor(u) and the weights along each axis are the fractional parts.
    double trilinear(const glm::dvec3& p) const {
        const glm::dvec3 u = voxelCoordinates(p) - 0.5;
        const glm::dvec3 lower = glm::floor(u);
        const glm::dvec3 w = u - lower;
        const glm::ivec3 base(lower);
        double sum = 0.0;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
            const double weight = (o.x ? w.x : 1.0 - w.x) * (o.y ? w.y : 1.0 - w.y) * (o.z ? w.z : 1.0 - w.z);
            sum += weight * voxel(base + o);
        }
        return sum;
    }

    const Volume& volume() const { return volume_; }
    glm::ivec3 dims() const { return dims_; }
    glm::dvec3 extent() const { return extent_; }
    Interpolation interpolation() const { return interpolation_; }

private:
    double tap(glm::ivec3 ijk) const {
        if (coefficients_.empty()) return voxel(ijk);
        ijk = glm::clamp(ijk, glm::ivec3(0), dims_ - 1);
        return coefficients_[std::size_t(ijk.x) + std::size_t(dims_.x) * (std::size_t(ijk.y) + std::size_t(dims_.y) * std::size_t(ijk.z))];
    }
    // The kernel's weights for the values at i-1 .. i+2 (or their derivatives).
    void weights(double t, bool derivative, double* w) const {
        const double t2 = t * t, t3 = t2 * t;
        if (interpolation_ == Interpolation::BSpline) {
            if (derivative) w[0] = -(1 - t) * (1 - t) / 2, w[1] = (3 * t2 - 4 * t) / 2, w[2] = (-3 * t2 + 2 * t + 1) / 2, w[3] = t2 / 2;
            else w[0] = (1 - t) * (1 - t) * (1 - t) / 6, w[1] = (3 * t3 - 6 * t2 + 4) / 6, w[2] = (-3 * t3 + 3 * t2 + 3 * t + 1) / 6, w[3] = t3 / 6;
        } else if (derivative) {
            w[0] = (-3 * t2 + 4 * t - 1) / 2, w[1] = (9 * t2 - 10 * t) / 2, w[2] = (-9 * t2 + 8 * t + 1) / 2, w[3] = (3 * t2 - 2 * t) / 2;
        } else {
            w[0] = (-t3 + 2 * t2 - t) / 2, w[1] = (3 * t3 - 5 * t2 + 2) / 2, w[2] = (-3 * t3 + 4 * t2 + t) / 2, w[3] = (t3 - t2) / 2;
        }
    }

    std::vector<float> coefficients_;
    const Volume& volume_;
    glm::ivec3 dims_;
    glm::dvec3 extent_;
    Interpolation interpolation_;
};

}  // namespace voxlab
