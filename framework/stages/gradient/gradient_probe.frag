#version 330 core
// Probe for the function check "gradient_random_points": gradient_central()
// and gradient_sobel() of the gradient stage on the probe's volume. The
// program is built with u_interpolation = 2 (the GPU's own filtering), so
// the check does not depend on the submission's sampling stage.
// Input 0: the world position. Results: central, Sobel.
#include "voxlab/volume.glsl"
#include "probes/probe.glsl"
#include "gradient/gradient.glsl"

void main() {
    vec3 p = PROBE_INPUT(0).xyz;
    probe_write(vec4(gradient_central(p), 0.0), vec4(gradient_sobel(p), 0.0));
}
