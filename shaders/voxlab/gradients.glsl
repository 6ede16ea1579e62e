// voxlab GLSL library: the gradient of the volume at a point.
//
// gradient_at(p) returns grad f in data units per unit length (the smallest
// voxel spacing; see framework/include/volume/voxlab/gradients.h). Renderers that
// shade or use a 2D transfer function declare two parameters that choose
// how it is obtained:
//   sobel                  0: central differences (6 samples), 1: the
//                          26-neighbour estimator (smoother, 54 samples);
//   precomputed_gradients  1: read the gradient volume the CPU computed with
//                          that estimator at the voxels (u_gradient_volume,
//                          filtered linearly); 0: estimate on the fly here.
// The on-the-fly estimators are the "gradient" stage (gradient/gradient.glsl).
// With a cubic interpolation (3, 4) the gradient is the cubic kernel's own
// derivative instead (gradient_cubic, the "cubic" stage), whatever these say.
#ifndef VOXLAB_GRADIENTS_GLSL
#define VOXLAB_GRADIENTS_GLSL

#include "voxlab/volume.glsl"
#include "gradient/gradient.glsl"

uniform int u_sobel;
uniform int u_precomputed_gradients;
uniform sampler3D u_gradient_volume;

vec3 gradient_at(vec3 p) {
    if (u_interpolation >= 3) return gradient_cubic(p);  // the cubic kernel's own derivative
    if (u_precomputed_gradients != 0) return filtered(u_gradient_volume, p / u_volume_extent).xyz;
    return u_sobel != 0 ? gradient_sobel(p) : gradient_central(p);
}

#endif
