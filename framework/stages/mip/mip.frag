#version 330 core
// Renderer "mip": maximum intensity projection. The stage itself,
// mip_ray(), is implemented in mip/mip.glsl (reference/ or a submission);
// largest_over_runs() calls it once per run between empty bricks.
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "mip/mip.glsl"
#define RUN_LARGEST mip_ray
#include "voxlab/runs.glsl"

out vec4 frag_color;

void main() {
    Ray ray = camera_ray();
    if (!clip_to_volume(ray) || !in_this_brick(ray) || sample_count(ray) < 1) {
        frag_color = nothing();
        return;
    }
    frag_color = finish(display_value(largest_over_runs(ray)));
}
