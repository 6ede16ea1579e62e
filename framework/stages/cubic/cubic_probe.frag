#version 330 core
// Probe for the function check "cubic_random_points": the cubic stage on
// the probe's volume, built with u_interpolation = 4 (Catmull-Rom).
// Input 0: the world position. Input 1: (t, kernel, derivative?, 0).
// Results: (sample_cubic, gradient_cubic) at the position; the kernel's four
// weights at t, or their derivatives when input 1's z is 1.
#include "voxlab/volume.glsl"
#include "probes/probe.glsl"

void main() {
    vec3 p = PROBE_INPUT(0).xyz;
    vec4 w = PROBE_INPUT(1);
    vec4 weights = w.z != 0.0 ? cubic_derivative_weights(w.x, int(w.y)) : cubic_weights(w.x, int(w.y));
    probe_write(vec4(sample_cubic(p), gradient_cubic(p)), weights);
}
