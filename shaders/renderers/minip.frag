#version 330 core
// Renderer "minip": minimum intensity projection. The stage itself,
// minip_ray(), is implemented in minip/minip.glsl (reference/ or a submission).
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "minip/minip.glsl"

out vec4 frag_color;

void main() {
    Ray ray = camera_ray();
    if (!clip_to_volume(ray) || sample_count(ray) < 1) {
        frag_color = nothing();
        return;
    }
    frag_color = finish(display_value(minip_ray(ray)));
}
