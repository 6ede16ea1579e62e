// Student starter code, generated from reference/composite/composite.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
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
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

// Pre-classification: the 8 voxels around p classified first, their
// opacity-weighted colours interpolated trilinearly (with nearest
// interpolation: the one voxel containing p).
vec4 classify_pre(vec3 p) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

// Moves the start of the ray by (pixel_random() - 1/2) steps, a random
// offset in [-1/2, 1/2) of a step, centred so that the ray keeps its
// samples on average (the same offset for a pixel in every frame). Sampling every ray at the same depths makes
// wood-grain rings on smooth surfaces; jittering the start turns them into
// fine noise (the ray still takes its samples one step apart).
void jitter_start(inout Ray ray) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
}

// Front-to-back compositing with early ray termination. Returns the
// premultiplied colour and the opacity of the ray.
vec4 composite_front_to_back(Ray ray) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

// Back-to-front compositing: the same image, without early termination.
vec4 composite_back_to_front(Ray ray) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

#endif
