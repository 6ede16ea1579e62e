// Stage: gradient estimation.
//
// The gradient grad f points where the value grows fastest; its length says
// how fast. Shading uses its direction as a surface normal, the 2D transfer
// function its length. The volume only has samples, so the derivative is
// estimated by finite differences of sample_volume().
//
// Work along each axis a with h = the voxel spacing on that axis
// (u_volume_extent / u_volume_dims), at the two points p - h e_a and
// p + h e_a. Near the faces of the volume those points may fall outside the
// range of voxel centres, [h/2, extent - h/2]; clamp them into it and divide
// by the distance that is left (a one-sided difference). That keeps the
// estimate exact on a linear field right up to the faces.
//
// Return the gradient per unit length, the smallest voxel spacing: multiply
// the per-world-unit result by u_min_spacing. (On a volume of spacing 1 both
// are the same.) framework/include/volume/voxlab/gradients.h computes the same
// estimators on the CPU, at the voxels.
#ifndef VOXLAB_STAGE_GRADIENT_GLSL
#define VOXLAB_STAGE_GRADIENT_GLSL

#include "voxlab/volume.glsl"

// The derivative along `axis` (0, 1, 2) at p, from the samples at
// p -+ h e_axis (clamped as above), in data units per world unit.
float axis_difference(vec3 p, int axis) {
    // BEGIN SOLUTION
    vec3 spacing = u_volume_extent / vec3(u_volume_dims);
    float lowest = 0.5 * spacing[axis], highest = u_volume_extent[axis] - 0.5 * spacing[axis];
    vec3 a = p, b = p;
    a[axis] = clamp(p[axis] - spacing[axis], lowest, highest);
    b[axis] = clamp(p[axis] + spacing[axis], lowest, highest);
    float distance = b[axis] - a[axis];
    if (distance <= 0.0) return 0.0;
    return (sample_volume(b) - sample_volume(a)) / distance;
    // END SOLUTION
}

// Central differences: 6 samples, one pair per axis.
vec3 gradient_central(vec3 p) {
    // BEGIN SOLUTION
    return vec3(axis_difference(p, 0), axis_difference(p, 1), axis_difference(p, 2)) * u_min_spacing;
    // END SOLUTION
}

// The 26-neighbour (Sobel-like) estimator: along each axis, average the
// central differences taken on the 3 x 3 neighbouring lines parallel to it,
// with weights (2 - |da|) (2 - |db|) for offsets da, db in {-1, 0, 1} voxels
// across the line (the smoothing kernel [1 2 1] in both directions; the
// weights add up to 16). Noise is smoothed; a linear field stays exact.
vec3 gradient_sobel(vec3 p) {
    // BEGIN SOLUTION
    vec3 spacing = u_volume_extent / vec3(u_volume_dims);
    vec3 g = vec3(0.0);
    for (int axis = 0; axis < 3; ++axis) {
        int a = (axis + 1) % 3, b = (axis + 2) % 3;
        float sum = 0.0;
        for (int da = -1; da <= 1; ++da) {
            for (int db = -1; db <= 1; ++db) {
                vec3 q = p;
                q[a] += float(da) * spacing[a];
                q[b] += float(db) * spacing[b];
                sum += float((2 - abs(da)) * (2 - abs(db))) * axis_difference(q, axis);
            }
        }
        g[axis] = sum / 16.0;
    }
    return g * u_min_spacing;
    // END SOLUTION
}

#endif
