// voxlab: splatting (Westover 1990), object-order volume rendering that
// throws each voxel at the image as a blurred dot: the stage's C++ contract
// and the framework's side of it.
//
// Each voxel that the transfer function does not hide becomes a Gaussian
// blob of absorbing, emitting matter centred on the voxel, with standard
// deviation sigma (the renderer's `radius`, in smallest spacings). Its
// integral along a ray is a 2D Gaussian "footprint" on the image: a pixel
// at distance r (world units, across the view) from the voxel's projected
// centre sees the voxel's matter over an effective length
//     L(r) = V g(r),  g(r) = exp(-r^2 / (2 sigma^2)) / (2 pi sigma^2),
// V the voxel's volume (the product of its spacings). The splat's opacity
// there is the transfer function's alpha (per unit length) over L(r) unit
// lengths: a = 1 - (1 - alpha)^(L(r) / u), u the smallest spacing. Summed
// over the image plane L is V: a splat puts exactly one voxel's worth of
// matter into the picture (test_splatting). Splats are drawn back to front
// and laid "over" each other.
//
// The splat stage (reference/splat/): the order of the walk (splatOrder,
// C++) and the footprint and its opacity (splat.glsl, GLSL).
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/transfer_function.h"
#include "voxlab/volume.h"

namespace voxlab {

// --- The splat stage (C++; reference/splat/splat_order.cpp) -----------------

// How splatting walks the voxels back to front for a view direction d
// (from the eye into the scene, any length > 0): three nested loops, the
// outer one along axes[0], the inner one along axes[2]; step[a] is -1 when
// axis a is walked from its last voxel down to 0, +1 when up from 0.
// A voxel farther along d is drawn first: axis a runs downwards when
// d[a] > 0 (the far voxels have the larger indices), upwards otherwise. The
// outer loop runs along the axis most nearly parallel to d (the largest
// |d[a]|), the middle along the next, ties going to the lower axis, so
// that each slice of the outer loop is drawn whole before the next
// (Westover's slices).
struct SplatOrder {
    std::array<int, 3> axes{0, 1, 2};
    std::array<int, 3> step{1, 1, 1};
};
SplatOrder splatOrder(glm::dvec3 viewDirection);

// --- The framework's side -----------------------------------------------------

// The voxels `tf` does not hide (opacity > 0 at their value), in `order`:
// each as its world centre (xyz) and value (w).
std::vector<glm::vec4> splatPoints(const Volume& volume, const TransferFunction& tf, const SplatOrder& order);

}  // namespace voxlab

// The stage's C++ functions for the stage table (voxlab/stage_library.h):
// X(name, return type, parameter types).
#define VOXLAB_STAGE_FUNCTIONS_splat(X) X(splatOrder, SplatOrder, (glm::dvec3))
