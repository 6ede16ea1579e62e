#version 330 core
// Renderer "mip": maximum intensity projection. The stage itself,
// mip_ray(), is implemented in mip/mip.glsl (reference/ or a submission).
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "mip/mip.glsl"

out vec4 frag_color;

void main() {
    Ray ray = camera_ray();
    if (!clip_to_volume(ray) || sample_count(ray) < 1) {
        frag_color = nothing();
        return;
    }
    frag_color = finish(display_value(mip_ray(ray)));
}
