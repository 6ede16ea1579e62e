// voxlab: the shear-warp factorisation (Lacroute and Levoy, SIGGRAPH 1994)
// for orthographic views: the shear-warp stage's C++ contract.
//
// Ray casting resamples the volume along every ray, at positions that fall
// anywhere between voxels. Shear-warp chooses a frame in which every ray
// runs straight along one axis of the volume, the principal axis c (the one
// most nearly parallel to the rays). Each slice of voxels perpendicular to c
// is shifted ("sheared") so that the rays pass through all slices at the same
// 2D position: slice x_c = k moves by k (shear_a, shear_b). Then the slices
// are composited front to back into an intermediate image whose pixels are
// one voxel apart and whose rays are straight lines through the stack, each
// slice read with 2D bilinear interpolation only. A final 2D affine warp
// takes the intermediate image to the screen.
//
// Coordinates. Continuous voxel coordinates x (voxel i spans [i, i+1], its
// centre at i + 1/2; world = x * spacing). The principal axis c and the two
// others a = (c + 1) % 3, b = (c + 2) % 3. With v the view direction in
// voxel units (v = forward / spacing, component by component),
//     shear_a = -v_a / v_c,   shear_b = -v_b / v_c,
// and a point x lands on the intermediate image at
//     (u, w) = (x_a + shear_a x_c + offset_a,  x_b + shear_b x_c + offset_b),
// where the offsets keep the whole sheared box at u, w >= 0:
// offset_a = max(0, -shear_a n_c) (n_c voxels along c; likewise for b).
// Points on one ray share (u, w): that is the shear. The warp maps (u, w) to
// the image pixel (continuous pixel coordinates, as Camera::ray takes them)
// that the camera shows the ray on: pixel = warp * (u, w, 1).
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "voxlab/camera.h"

namespace voxlab {

struct ShearWarp {
    int axis = 2;                // the principal axis c
    int front = 0;               // the index of the slice nearest the viewer: 0 or n_c - 1
    glm::dvec2 shear{0.0};       // (shear_a, shear_b), voxels of shift per slice
    glm::dvec2 offset{0.0};      // (offset_a, offset_b)
    glm::ivec2 size{0};          // the intermediate image: ceil(n_a + |shear_a| n_c), same for b
    glm::dmat3 warp{1.0};        // (u, w, 1) -> (pixel x, pixel y, 1); column-major (glm)
};

// --- The stage (C++; reference/shearwarp/) ------------------------------------

// The factorisation for an orthographic camera over a volume of `dims`
// voxels with `spacing`, as above. Throws voxlab::Error for a perspective
// camera (not supported: Lacroute's perspective form scales each slice too).
ShearWarp factorShearWarp(const Camera& camera, glm::ivec3 dims, glm::dvec3 spacing);

}  // namespace voxlab

// The stage's C++ functions for the stage table (voxlab/stage_library.h):
// X(name, return type, parameter types).
#define VOXLAB_STAGE_FUNCTIONS_shearwarp(X) X(factorShearWarp, ShearWarp, (const Camera&, glm::ivec3, glm::dvec3))
