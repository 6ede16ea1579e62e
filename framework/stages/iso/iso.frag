#version 330 core
// Renderer "iso": the first crossing of the isovalue, as an opaque shaded
// surface of one colour or, with `depth`, as its distance (depth_grey: near
// white, far black). The stage is iso_hit(), in iso/iso.glsl; the normal
// comes from the gradient stage and the lighting from the shading stage.
// iso_hit() gets the ray in runs between empty bricks (voxlab/runs.glsl).
#include "voxlab/ray.glsl"
#include "voxlab/output.glsl"
#include "voxlab/lighting.glsl"
#include "iso/iso.glsl"
#define RUN_CROSSING iso_hit
#include "voxlab/runs.glsl"

uniform float u_color_r;
uniform float u_color_g;
uniform float u_color_b;
uniform int u_depth;

out vec4 frag_color;

void main() {
    Ray ray = camera_ray();
    float t;
    if (!clip_to_volume(ray) || !in_this_brick(ray) || !crossing_over_runs(ray, t)) {
        frag_color = nothing();
        return;
    }
    if (u_depth != 0) {
        frag_color = finish(vec4(vec3(depth_grey(ray, t)), 1.0));
        return;
    }
    vec3 colour = vec3(u_color_r, u_color_g, u_color_b);
    frag_color = finish(vec4(shade_sample(colour, point_at(ray, t), ray), 1.0));
}
