// Stage: direct volume rendering by compositing (the emission-absorption
// model).
//
// Each sample has a colour c and an opacity a (from the transfer function).
// Along a ray the light that reaches the eye is
//     C = sum_m T_m a_m c_m,   with T_m = prod_{k<m} (1 - a_k)
// (Max, "Optical models for direct volume rendering", 1995): sample m
// emits a_m c_m and everything in front of it lets T_m of that through.
//
// Front to back, keep the accumulated colour C (premultiplied) and opacity A:
//     C += (1 - A) a c,   A += (1 - A) a.
// Once A is close to 1 nothing behind can show: stop early when
// A >= u_early_termination (early ray termination).
// Back to front, start at the last sample and lay each one over the result:
//     C = a c + (1 - a) C,   A = a + (1 - a) A.
// Both give the same C and A (without early termination).
//
// Opacity correction: transfer-function opacities are per unit length (the
// smallest spacing). A sample stands for u_step_units of that length, so use
// a = opacity_correction(alpha, u_step_units) = 1 - (1 - alpha)^step.
//
// Classification, i.e. where the transfer function is applied:
//  - post-classification (default): interpolate the data value, then
//    classify it: transfer_function(sample_volume(p));
//  - pre-classification: classify the 8 voxels around p, then interpolate
//    their colours. Interpolate opacity-weighted colours (a c, a) and divide
//    by a afterwards, or a bright transparent voxel bleeds its colour into
//    its opaque neighbours (Wittenbrink et al., 1998).
//
// The renderer's entry shader supplies sample_colour(p, ray): classification
// and shading of one sample (the 1D or the 2D transfer function), and calls
// one of the two compositing loops.
#ifndef VOXLAB_STAGE_COMPOSITE_GLSL
#define VOXLAB_STAGE_COMPOSITE_GLSL

#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"

uniform float u_early_termination;

// Colour (rgb, not premultiplied) and opacity per unit length (a) of the
// sample at p; defined by the renderer's entry shader.
vec4 sample_colour(vec3 p, Ray ray);

// Post-classification: the transfer function of the interpolated value.
vec4 classify_post(vec3 p) {
    // BEGIN SOLUTION
    return transfer_function(sample_volume(p));
    // END SOLUTION
}

// Pre-classification: the 8 voxels around p classified first, their
// opacity-weighted colours interpolated trilinearly (with nearest
// interpolation: the one voxel containing p).
vec4 classify_pre(vec3 p) {
    // BEGIN SOLUTION
    if (u_interpolation == 0) return transfer_function(sample_nearest(p));
    vec3 u = voxel_coordinates(p) - 0.5;
    vec3 lower = floor(u);
    vec3 w = u - lower;
    ivec3 i = ivec3(lower);
    vec4 sum = vec4(0.0);
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 o = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        vec3 weights = mix(1.0 - w, w, vec3(o));
        vec4 c = transfer_function(voxel_value(i + o));
        sum += weights.x * weights.y * weights.z * vec4(c.rgb * c.a, c.a);
    }
    return sum.a > 0.0 ? vec4(sum.rgb / sum.a, sum.a) : vec4(0.0);
    // END SOLUTION
}

// Moves the start of the ray by (pixel_random() - 1/2) steps, a random
// offset in [-1/2, 1/2) of a step, centred so that the ray keeps its
// samples on average (the same offset for a pixel in every frame). Sampling every ray at the same depths makes
// wood-grain rings on smooth surfaces; jittering the start turns them into
// fine noise (the ray still takes its samples one step apart).
void jitter_start(inout Ray ray) {
    // BEGIN SOLUTION
    ray.t_entry += (pixel_random() - 0.5) * u_step;
    // END SOLUTION
}

// Front-to-back compositing with early ray termination. Returns the
// premultiplied colour and the opacity of the ray.
vec4 composite_front_to_back(Ray ray) {
    // BEGIN SOLUTION
    vec4 result = vec4(0.0);
    int n = sample_count(ray);
    for (int m = 0; m < n; ++m) {
        vec4 c = sample_colour(sample_position(ray, m), ray);
        float a = opacity_correction(c.a, u_step_units);
        result.rgb += (1.0 - result.a) * a * c.rgb;
        result.a += (1.0 - result.a) * a;
        if (result.a >= u_early_termination) break;
    }
    return result;
    // END SOLUTION
}

// Back-to-front compositing: the same image, without early termination.
vec4 composite_back_to_front(Ray ray) {
    // BEGIN SOLUTION
    vec4 result = vec4(0.0);
    for (int m = sample_count(ray) - 1; m >= 0; --m) {
        vec3 p = sample_position(ray, m);
        vec4 c = sample_colour(p, ray);
        float a = opacity_correction(c.a, u_step_units);
        result.rgb = a * c.rgb + (1.0 - a) * result.rgb;
        result.a = a + (1.0 - a) * result.a;
    }
    return result;
    // END SOLUTION
}

#endif
