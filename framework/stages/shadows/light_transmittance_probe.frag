#version 330 core
// Probe for the function check "light_transmittance_random":
// light_transmittance() of the shadows stage, with the volume and transfer
// function the check uploads. Input 0: (p, step); input 1: (to_light, 0).
// Result: the transmittance in x.
#include "voxlab/not_implemented.glsl"
#include "probes/probe.glsl"
#include "shadows/shadows.glsl"

void main() {
    vec4 in0 = PROBE_INPUT(0);
    vec4 in1 = PROBE_INPUT(1);
    probe_write(vec4(light_transmittance(in0.xyz, in1.xyz, in0.w), 0.0, 0.0, 0.0), vec4(0.0));
}
