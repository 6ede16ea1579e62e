// Student starter code, generated from reference/mida/mida.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: maximum intensity difference accumulation (MIDA).
//
// S. Bruckner and M. E. Groeller, "Instant Volume Visualization using
// Maximum Intensity Difference Accumulation", Computer Graphics Forum 28(3),
// 2009. Direct volume rendering (compositing) needs a transfer function
// that hides what is in front; MIP needs none but has no depth. MIDA
// composites front to back like DVR, but a sample that raises the ray's
// running maximum pushes back what was accumulated before it, by how much
// it raised it:
//
//     v_i     = (f_i - lo) / (hi - lo), clamped to [0, 1]   the sample, normalised
//                                                          to the range [lo, hi]
//     delta_i = v_i - max(v_0 .. v_{i-1})  if larger, else 0  (the maximum before
//                                                          the first sample is 0)
//     beta_i  = 1 - delta_i * (1 + min(gamma, 0))
//     C_i     = beta_i C_{i-1} + (1 - beta_i A_{i-1}) a_i c_i
//     A_i     = beta_i A_{i-1} + (1 - beta_i A_{i-1}) a_i
//
// c_i and a_i are the transfer function's colour and opacity at f_i, the
// opacity corrected for the step (opacity_correction(alpha, u_step_units));
// lo, hi = u_value_range; C and A start at 0. gamma (u_gamma, in [-1, 1])
// moves between the techniques: at -1 beta is 1 and this is compositing
// without early termination; at 0 it is MIDA; above 0 the result is blended
// towards MIP, (1 - gamma) * MIDA + gamma * display_value(the largest
// sample), which at 1 is the MIP renderer's pixel.
#ifndef VOXLAB_STAGE_MIDA_GLSL
#define VOXLAB_STAGE_MIDA_GLSL

#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"

uniform float u_gamma;  // -1: compositing, 0: MIDA, 1: MIP

// Returns the ray's colour, premultiplied, and its opacity.
vec4 mida_ray(Ray ray) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

#endif
