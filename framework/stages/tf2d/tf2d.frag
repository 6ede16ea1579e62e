#version 330 core
// Renderer "tf2d": direct volume rendering classified by the 2D transfer
// function over (value, gradient magnitude). The stage is tf2d_classify(),
// in tf2d/tf2d.glsl; compositing is the composite stage's.
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "voxlab/lighting.glsl"
#include "composite/composite.glsl"
#define RUN_FRONT_TO_BACK composite_front_to_back
#define RUN_BACK_TO_FRONT composite_back_to_front
#include "voxlab/runs.glsl"
#include "tf2d/tf2d.glsl"

uniform int u_back_to_front;
uniform int u_jitter;

out vec4 frag_color;

vec4 sample_colour(vec3 p, Ray ray) {
    vec3 g = gradient_at(p);
    vec4 c = tf2d_classify(sample_volume(p), length(g));
    if (c.a > 0.0) c.rgb = shade_sample_with_gradient(c.rgb, g, ray);
    return c;
}

void main() {
    Ray ray = camera_ray();
    if (!clip_to_volume(ray)) {
        frag_color = nothing();
        return;
    }
    if (u_jitter != 0) jitter_start(ray);
    if (!in_this_brick(ray)) {
        frag_color = nothing();
        return;
    }
    frag_color = finish(u_back_to_front != 0 ? back_to_front_over_runs(ray) : front_to_back_over_runs(ray));
}
