#version 330 core
// Probe for the function check "trilinear_random_points": sample_trilinear()
// and sample_nearest() of the sampling stage on the probe's volume.
// Input 0: the world position. Result: (trilinear, nearest).
#include "voxlab/volume.glsl"
#include "probes/probe.glsl"

void main() {
    vec3 p = PROBE_INPUT(0).xyz;
    probe_write(vec4(sample_trilinear(p), sample_nearest(p), 0.0, 0.0), vec4(0.0));
}
