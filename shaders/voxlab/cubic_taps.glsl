// voxlab GLSL library: what the cubic stage's kernels are applied to.
//
// Catmull-Rom interpolates the voxels themselves; the cubic B-spline needs
// prefiltered coefficients (framework/src/volume/bspline.cpp), one per
// voxel, computed on the CPU and uploaded as a float texture
// (u_bspline_coefficients) when the scene asks for "bspline". Both are read
// with indices clamped to the grid, as voxel_value() is.
#ifndef VOXLAB_CUBIC_TAPS_GLSL
#define VOXLAB_CUBIC_TAPS_GLSL

uniform sampler3D u_bspline_coefficients;

float cubic_tap(ivec3 ijk) {
    if (u_interpolation != 3) return voxel_value(ijk);
    ijk = clamp(ijk, ivec3(0), u_volume_dims - 1);
    return texelFetch(u_bspline_coefficients, ijk, 0).r;
}

#endif
