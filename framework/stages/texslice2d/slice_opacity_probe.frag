#version 330 core
// Probe for the function check "slice_axis_random": slice_opacity() of the
// texslice2d stage. u_stack_axis, u_slice_spacing and u_min_spacing are set
// per case. Input 0: the ray direction (xyz) and alpha (w). Result: the
// slice's opacity.
#include "voxlab/volume.glsl"
#include "voxlab/classify.glsl"
#include "probes/probe.glsl"
#include "texslice2d/texslice2d.glsl"

void main() {
    vec4 input0 = PROBE_INPUT(0);
    probe_write(vec4(slice_opacity(input0.w, input0.xyz), 0.0, 0.0, 0.0), vec4(0.0));
}
