#version 330 core
// The pre-integration table (the preintegration stage): texel (i, j) is the
// segment from front value lo + i (hi - lo) / (size - 1) to back value
// lo + j (hi - lo) / (size - 1), one step long, integrated by the stage's
// preintegrate_segment() with one sub-segment per table texel or
// transfer-function entry crossed, whichever is finer (at least 1, at most
// 256): each piece then spans at most one linear piece of the function, and
// the midpoint rule's error on it is second order in its width.
#include "voxlab/classify.glsl"
#include "voxlab/ray.glsl"
#include "preintegration/preintegration.glsl"

uniform ivec3 u_precompute_size;
out vec4 frag_color;

void main() {
    vec2 f = (gl_FragCoord.xy - 0.5) / vec2(u_precompute_size.xy - 1);
    vec2 values = mix(vec2(u_tf_range.x), vec2(u_tf_range.y), f);
    float cells = abs(f.y - f.x) * float(max(u_tf_size - 1, u_precompute_size.x - 1));
    frag_color = preintegrate_segment(values.x, values.y, u_step_units, clamp(int(ceil(cells - 1e-3)), 1, 256));
}
