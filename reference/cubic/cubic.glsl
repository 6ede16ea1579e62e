// Stage: cubic reconstruction (tricubic interpolation).
//
// Trilinear interpolation is continuous but its derivative jumps at every
// voxel boundary: isosurfaces show facets and shading shows the grid. Cubic
// kernels read the 4 voxels around the point on each axis (4x4x4 = 64 in
// 3D) and give smoother fields (Marschner and Lobb 1994; Möller et al.
// 1997). Two kernels, each a cubic polynomial in the fraction t in [0, 1)
// between the voxel centres i and i+1, weighting the 4 values at i-1, i,
// i+1, i+2:
//
//   Catmull-Rom (interpolating, C1, reproduces quadratics; overshoots a
//   little at sharp edges):
//     w0 = (-t^3 + 2t^2 - t) / 2        w1 = (3t^3 - 5t^2 + 2) / 2
//     w2 = (-3t^3 + 4t^2 + t) / 2       w3 = (t^3 - t^2) / 2
//   Cubic B-spline (C2, never overshoots its coefficients, but blurs: it
//   does not pass through the values themselves):
//     w0 = (1 - t)^3 / 6                w1 = (3t^3 - 6t^2 + 4) / 6
//     w2 = (-3t^3 + 3t^2 + 3t + 1) / 6  w3 = t^3 / 6
//
// The B-spline interpolates when it is applied to prefiltered coefficients
// instead of the voxels (Unser 1999): the framework computes them on the CPU
// (framework/src/volume/bspline.cpp) and cubic_tap() reads them for it.
// Each kernel's four weights sum to 1 for every t; the weights of the
// derivative (d/dt of each) sum to 0.
//
// The kernel in use is u_interpolation: 3 the B-spline, 4 Catmull-Rom.
#ifndef VOXLAB_STAGE_CUBIC_GLSL
#define VOXLAB_STAGE_CUBIC_GLSL

#include "voxlab/volume.glsl"
#include "voxlab/cubic_taps.glsl"

// The four weights of the kernel (3: B-spline, 4: Catmull-Rom) for the
// values at i-1, i, i+1, i+2, where t in [0, 1) is the point's fraction
// between the centres of voxels i and i+1.
vec4 cubic_weights(float t, int kernel) {
    // BEGIN SOLUTION
    float t2 = t * t, t3 = t2 * t;
    if (kernel == 3)
        return vec4((1.0 - t) * (1.0 - t) * (1.0 - t), 3.0 * t3 - 6.0 * t2 + 4.0,
                    -3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0, t3) / 6.0;
    return vec4(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2) / 2.0;
    // END SOLUTION
}

// Their derivatives with respect to t.
vec4 cubic_derivative_weights(float t, int kernel) {
    // BEGIN SOLUTION
    float t2 = t * t;
    if (kernel == 3) return vec4(-(1.0 - t) * (1.0 - t), 3.0 * t2 - 4.0 * t, -3.0 * t2 + 2.0 * t + 1.0, t2) / 2.0;
    return vec4(-3.0 * t2 + 4.0 * t - 1.0, 9.0 * t2 - 10.0 * t, -9.0 * t2 + 8.0 * t + 1.0, 3.0 * t2 - 2.0 * t) / 2.0;
    // END SOLUTION
}

// The cubic reconstruction at world position p: shift the voxel
// coordinates by -1/2 (centres on integers, as for trilinear), take
// i = floor and t = the fraction on each axis, and sum the 64 taps
// cubic_tap(i + (a, b, c) - 1), a, b, c in 0..3, each weighted by the
// product of its three axes' weights.
float sample_cubic(vec3 p) {
    // BEGIN SOLUTION
    vec3 u = voxel_coordinates(p) - 0.5;
    vec3 lower = floor(u);
    vec3 t = u - lower;
    ivec3 base = ivec3(lower) - 1;
    vec4 wx = cubic_weights(t.x, u_interpolation);
    vec4 wy = cubic_weights(t.y, u_interpolation);
    vec4 wz = cubic_weights(t.z, u_interpolation);
    float sum = 0.0;
    for (int c = 0; c < 4; ++c)
        for (int b = 0; b < 4; ++b)
            for (int a = 0; a < 4; ++a)
                sum += wx[a] * wy[b] * wz[c] * cubic_tap(base + ivec3(a, b, c));
    return sum;
    // END SOLUTION
}

// The gradient of that reconstruction, in data units per unit length (the
// smallest spacing): on each axis the derivative weights replace that
// axis's weights, which gives d f / d u (per voxel); a voxel is spacing
// world units long, so d f / d world = (d f / d u) / spacing, times
// u_min_spacing for unit lengths.
vec3 gradient_cubic(vec3 p) {
    // BEGIN SOLUTION
    vec3 u = voxel_coordinates(p) - 0.5;
    vec3 lower = floor(u);
    vec3 t = u - lower;
    ivec3 base = ivec3(lower) - 1;
    vec4 wx = cubic_weights(t.x, u_interpolation), dx = cubic_derivative_weights(t.x, u_interpolation);
    vec4 wy = cubic_weights(t.y, u_interpolation), dy = cubic_derivative_weights(t.y, u_interpolation);
    vec4 wz = cubic_weights(t.z, u_interpolation), dz = cubic_derivative_weights(t.z, u_interpolation);
    vec3 g = vec3(0.0);
    for (int c = 0; c < 4; ++c)
        for (int b = 0; b < 4; ++b)
            for (int a = 0; a < 4; ++a) {
                float f = cubic_tap(base + ivec3(a, b, c));
                g += f * vec3(dx[a] * wy[b] * wz[c], wx[a] * dy[b] * wz[c], wx[a] * wy[b] * dz[c]);
            }
    vec3 spacing = u_volume_extent / vec3(u_volume_dims);
    return g / spacing * u_min_spacing;
    // END SOLUTION
}

#endif
