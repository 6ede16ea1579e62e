#version 330 core
// Renderer "slab_mip": MIP of a slab perpendicular to the view. The stages
// are clip_to_slab() (slab_mip/slab_mip.glsl) and mip_ray() (mip/mip.glsl).
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "mip/mip.glsl"
#include "slab_mip/slab_mip.glsl"
#define RUN_LARGEST mip_ray
#include "voxlab/runs.glsl"

out vec4 frag_color;

void main() {
    Ray ray = camera_ray();
    if (!clip_to_volume(ray) || !clip_to_slab(ray) || !in_this_brick(ray) || sample_count(ray) < 1) {
        frag_color = nothing();
        return;
    }
    frag_color = finish(display_value(largest_over_runs(ray)));
}
