#version 330 core
// Renderer "average": the mean value along each ray. The stage itself,
// average_ray(), is implemented in average/average.glsl (reference/ or a submission).
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "average/average.glsl"

out vec4 frag_color;

void main() {
    Ray ray = camera_ray();
    if (!clip_to_volume(ray) || sample_count(ray) < 1) {
        frag_color = nothing();
        return;
    }
    frag_color = finish(display_value(average_ray(ray)));
}
