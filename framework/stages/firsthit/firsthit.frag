#version 330 core
// Renderer "firsthit": the first sample at or above a threshold, shown by
// its value (grey window or transfer function) or, with `depth`, by its
// distance (depth_grey: near white, far black). The stage is first_hit(),
// in firsthit/firsthit.glsl, called once per run between empty bricks
// (voxlab/runs.glsl).
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "firsthit/firsthit.glsl"
#define RUN_FIRST_HIT first_hit
#include "voxlab/runs.glsl"

uniform int u_depth;

out vec4 frag_color;

void main() {
    Ray ray = camera_ray();
    float t, value;
    if (!clip_to_volume(ray) || !in_this_brick(ray) || !first_hit_over_runs(ray, t, value)) {
        frag_color = nothing();
        return;
    }
    frag_color = finish(u_depth != 0 ? vec4(vec3(depth_grey(ray, t)), 1.0) : display_value(value));
}
