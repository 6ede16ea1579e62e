#version 330 core
// Probe for the function check "preintegrate_segment_random":
// preintegrate_segment() of the preintegration stage, with the transfer
// function the check uploads. Input 0: (front value, back value, length in
// unit lengths, sub-segments). Result: the segment's (premultiplied colour,
// opacity).
#include "voxlab/not_implemented.glsl"
#include "probes/probe.glsl"
#include "preintegration/preintegration.glsl"

void main() {
    vec4 in0 = PROBE_INPUT(0);
    probe_write(preintegrate_segment(in0.x, in0.y, in0.z, int(in0.w)), vec4(0.0));
}
