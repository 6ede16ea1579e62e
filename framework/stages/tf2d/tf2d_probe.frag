#version 330 core
// Probe for the function check "tf2d_classify_random": tf2d_classify() of
// the tf2d stage. The widgets (u_tf2d_*) are set per case. Input 0: (value,
// gradient magnitude). Result: colour and opacity.
#include "voxlab/not_implemented.glsl"
#include "probes/probe.glsl"
#include "tf2d/tf2d.glsl"

void main() {
    vec2 fg = PROBE_INPUT(0).xy;
    probe_write(tf2d_classify(fg.x, fg.y), vec4(0.0));
}
