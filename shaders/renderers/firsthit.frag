#version 330 core
// Renderer "firsthit": the first sample at or above a threshold, shown by
// its value (grey window or transfer function) or, with `depth`, by its
// distance (depth_grey: near white, far black). The stage is first_hit(),
// in firsthit/firsthit.glsl.
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "firsthit/firsthit.glsl"

uniform int u_depth;

out vec4 frag_color;

void main() {
    Ray ray = camera_ray();
    float t, value;
    bool inside = clip_to_volume(ray);
    if (inside) skip_empty_ends(ray);
    if (!inside || !first_hit(ray, t, value)) {
        frag_color = nothing();
        return;
    }
    frag_color = finish(u_depth != 0 ? vec4(vec3(depth_grey(ray, t)), 1.0) : display_value(value));
}
