// voxlab internals: reading a volume between voxels on the CPU, in double,
// as the README's conventions say (the ray profile and its scene classifier).
#pragma once

#include <glm/glm.hpp>

#include "voxlab/scene.h"
#include "voxlab/volume.h"

namespace voxlab {

// Reading the volume between voxels: continuous voxel coordinates put voxel
// i's cell at [i, i+1], so its centre is at i + 1/2; indices are clamped to
// the grid (the border value continues outwards).
class VolumeReader {
public:
    VolumeReader(const Volume& volume, Interpolation interpolation)
        : volume_(volume), dims_(volume.dims()), extent_(volume.extent()), interpolation_(interpolation) {}

    double voxel(glm::ivec3 ijk) const {
        ijk = glm::clamp(ijk, glm::ivec3(0), dims_ - 1);
        return volume_.value(ijk.x, ijk.y, ijk.z);
    }
    glm::dvec3 voxelCoordinates(const glm::dvec3& p) const { return p / extent_ * glm::dvec3(dims_); }

    double sample(const glm::dvec3& p) const {
        if (interpolation_ == Interpolation::Nearest) return voxel(glm::ivec3(glm::floor(voxelCoordinates(p))));
        return trilinear(p);  // "hardware" too: the GPU's filter, without its reduced-precision weights
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
    const Volume& volume_;
    glm::ivec3 dims_;
    glm::dvec3 extent_;
    Interpolation interpolation_;
};

}  // namespace voxlab
