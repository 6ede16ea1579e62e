#version 330 core
// Renderer "composite": direct volume rendering with the 1D transfer
// function. The stages are the compositing loops and the classification in
// composite/composite.glsl; shading is the gradient and shading stages. The
// features other stages bring (their folders' component.glsl) are called
// under their switches from the generated stages/composite/components.glsl:
// in place of the classification, on the classified sample, or on the lit
// one. The loops get the ray in runs between empty bricks (voxlab/runs.glsl).
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "voxlab/lighting.glsl"
#include "composite/composite.glsl"
#include "stages/composite/components.glsl"
#include "labels/labels.glsl"
#include "voxlab/fusion.glsl"
#define RUN_FRONT_TO_BACK composite_front_to_back
#define RUN_BACK_TO_FRONT composite_back_to_front
#include "voxlab/runs.glsl"

uniform int u_preclassify;
uniform int u_back_to_front;
uniform int u_jitter;
uniform int u_labelled;  // the scene has a label map
uniform int u_fused;     // the scene has a second volume

out vec4 frag_color;

vec4 sample_colour(vec3 p, Ray ray) {
    vec4 c;
    if (u_labelled != 0) {
        c = classify_labelled(p);
        if (u_label_distance_on != 0 && c.a > 0.0) c = apply_label_distance(c, label_at(p), p);
    } else {
        if (!components_classify(p, ray, c)) c = u_preclassify != 0 ? classify_pre(p) : classify_post(p);
        if (u_fused != 0) c = classify_fused(p, c);
    }
    c = components_classified(c, p, ray);
    if (c.a > 0.0) c.rgb = shade_sample(c.rgb, p, ray);
    return components_lit(c, p, ray);
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
