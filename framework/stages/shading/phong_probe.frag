#version 330 core
// Probe for the function check "phong_random": phong() of the shading
// stage. Inputs: 0 colour, 1 normal, 2 light, 3 view; u_ka, u_kd, u_ks,
// u_shininess and u_blinn are set per case. Result: the colour.
#include "voxlab/not_implemented.glsl"
#include "probes/probe.glsl"
#include "shading/shading.glsl"

void main() {
    vec3 colour = phong(PROBE_INPUT(0).rgb, PROBE_INPUT(1).xyz, PROBE_INPUT(2).xyz, PROBE_INPUT(3).xyz);
    probe_write(vec4(colour, 0.0), vec4(0.0));
}
