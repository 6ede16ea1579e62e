#version 330 core
// Probe for the function check "gradient_opacity_random":
// gradient_opacity_weight() of the gradient_opacity stage. Input 0:
// (gradient magnitude, low, high, unused). Result: the weight in x.
#include "voxlab/not_implemented.glsl"
#include "probes/probe.glsl"
#include "gradient_opacity/gradient_opacity.glsl"

void main() {
    vec4 in0 = PROBE_INPUT(0);
    probe_write(vec4(gradient_opacity_weight(in0.x, in0.y, in0.z), 0.0, 0.0, 0.0), vec4(0.0));
}
