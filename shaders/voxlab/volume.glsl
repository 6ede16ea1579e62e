// voxlab GLSL library: reading the volume.
//
// The volume is a 3D texture over the box [0, u_volume_extent] in world
// space (voxel (i,j,k) is centred at (i+1/2, j+1/2, k+1/2) * spacing). Values
// come back in the data's own units: texel * u_value_scale + u_value_offset.
//
// sample_volume(p) reads between voxels as the scene's "interpolation" says
// (u_interpolation): 0 nearest and 1 trilinear, both written out in the
// "sampling" stage (sampling/sampling.glsl) from voxel_value(); 2 the GPU's
// own linear filtering ("hardware"; in the grader, the same written out in
// float: voxlab/filtering.glsl); 3 the cubic B-spline and 4 Catmull-Rom,
// the "cubic" stage (cubic/cubic.glsl).
#ifndef VOXLAB_VOLUME_GLSL
#define VOXLAB_VOLUME_GLSL

#include "voxlab/not_implemented.glsl"
#include "voxlab/bricks.glsl"
#include "voxlab/filtering.glsl"

uniform sampler3D u_volume;
uniform ivec3 u_volume_dims;
uniform vec3 u_volume_extent;
uniform float u_value_scale;
uniform float u_value_offset;
uniform float u_min_spacing;
uniform vec2 u_value_range;  // the volume's smallest and largest value
uniform int u_interpolation;

// The value stored at voxel (i,j,k), clamped to the grid; no filtering.
// (A bricked volume's texture holds one brick: voxlab/bricks.glsl.)
float voxel_value(ivec3 ijk) {
    ijk = clamp(ijk, ivec3(0), u_volume_dims - 1);
    if (u_bricked != 0) ijk = clamp(ijk - u_brick_origin, ivec3(0), u_brick_texture_dims - 1);
    return texelFetch(u_volume, ijk, 0).r * u_value_scale + u_value_offset;
}

// World position -> continuous voxel coordinates: voxel i spans [i, i+1] on
// each axis, so its centre is at i + 1/2.
vec3 voxel_coordinates(vec3 p) {
    return p / u_volume_extent * vec3(u_volume_dims);
}

#include "sampling/sampling.glsl"
#include "cubic/cubic.glsl"

// The data value at world position p.
float sample_volume(vec3 p) {
    if (u_interpolation == 0) return sample_nearest(p);
    if (u_interpolation == 1) return sample_trilinear(p);
    if (u_interpolation >= 3) return sample_cubic(p);
    vec3 texture_position = u_bricked == 0 ? p / u_volume_extent
                                           : (voxel_coordinates(p) - vec3(u_brick_origin)) / vec3(u_brick_texture_dims);
    return filtered(u_volume, texture_position).r * u_value_scale + u_value_offset;
}

bool inside_volume(vec3 p) {
    return all(greaterThanEqual(p, vec3(0.0))) && all(lessThanEqual(p, u_volume_extent));
}

#endif
