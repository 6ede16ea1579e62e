// Student starter code, generated from reference/sampling/sampling.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: sampling the volume between voxels.
//
// The volume is only known at voxel centres. Every renderer asks for values
// at arbitrary world positions p, through sample_volume(p), which calls one
// of the two functions below (the scene's "interpolation").
//
// voxel_coordinates(p) gives p in voxel units: voxel i covers [i, i+1] on
// each axis, so its centre sits at i + 1/2. voxel_value(ivec3) reads one
// voxel, in data units, and clamps indices to the grid (so the volume's
// border value continues outwards, like GL's CLAMP_TO_EDGE).
#ifndef VOXLAB_STAGE_SAMPLING_GLSL
#define VOXLAB_STAGE_SAMPLING_GLSL

#include "voxlab/volume.glsl"

// Nearest neighbour: the value of the voxel whose cell contains p.
float sample_nearest(vec3 p) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return 0.0;
}

// Trilinear interpolation from the 8 voxel centres around p.
//
// Shift the coordinates by -1/2 so that voxel centres sit on integers; then
// the lower corner is i0 = floor(u) and the weights are w = u - i0 (each in
// [0, 1)). Interpolate along x on the four edges, then along y, then z:
//   f = (1-w.z) [ (1-w.y) ((1-w.x) f000 + w.x f100) + w.y (...) ] + w.z [...]
// Each of the 8 values is one voxel_value() call: no texture filtering, so
// the result is exact in float on every GPU.
float sample_trilinear(vec3 p) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return 0.0;
}

#endif
