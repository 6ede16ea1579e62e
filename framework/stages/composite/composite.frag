#version 330 core
// Renderer "composite": direct volume rendering with the 1D transfer
// function. The stages are the compositing loops and the classification in
// composite/composite.glsl; shading is the gradient and shading stages; with
// `gradient_opacity` the opacity is weighted by the gradient_opacity stage,
// with `ambient_occlusion` the colour darkened by the ambient_occlusion stage;
// with `preintegrated` each sample stands for the segment to the next one,
// classified by the preintegration stage's table; with `shadows` each lit
// colour is dimmed by the light volume that the shadows stage fills.
// The loops get the ray in runs between empty bricks (voxlab/runs.glsl).
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "voxlab/lighting.glsl"
#include "composite/composite.glsl"
#include "gradient_opacity/gradient_opacity.glsl"
#include "ambient_occlusion/ambient_occlusion.glsl"
#include "preintegration/preintegration.glsl"
#include "shadows/shadows.glsl"
#include "labels/labels.glsl"
#include "voxlab/fusion.glsl"
#define RUN_FRONT_TO_BACK composite_front_to_back
#define RUN_BACK_TO_FRONT composite_back_to_front
#include "voxlab/runs.glsl"

uniform int u_preclassify;
uniform int u_preintegrated;
uniform int u_back_to_front;
uniform int u_jitter;
uniform int u_gradient_opacity;
uniform float u_gradient_low;
uniform float u_gradient_high;
uniform int u_ambient_occlusion;
uniform float u_ao_radius;
uniform float u_ao_strength;
uniform int u_shadows;
uniform sampler3D u_light_volume;  // transmittance towards the light (shadows)
uniform int u_labelled;  // the scene has a label map
uniform int u_fused;     // the scene has a second volume

out vec4 frag_color;

// The light volume's transmittance for a sample at p, read one light-volume
// voxel towards the light: a sample just under a surface would otherwise
// read the surface's own shadow, interpolated, and the depth at which each
// ray first samples the surface would show as rings ("shadow acne"). The
// shift runs along the light ray, so what shadows p shadows it still.
float shadow_at(vec3 p) {
    vec3 texel = u_volume_extent / vec3(textureSize(u_light_volume, 0));
    vec3 q = p + min(texel.x, min(texel.y, texel.z)) * light_direction();
    return filtered(u_light_volume, q / u_volume_extent).r;
}

vec4 sample_colour(vec3 p, Ray ray) {
    vec4 c;
    if (u_labelled != 0) {
        c = classify_labelled(p);
        if (u_label_distance_on != 0 && c.a > 0.0) c = apply_label_distance(c, label_at(p), p);
    } else {
        c = u_preintegrated != 0 ? classify_preintegrated(p, ray)
            : u_preclassify != 0 ? classify_pre(p)
                                 : classify_post(p);
        if (u_fused != 0) c = classify_fused(p, c);
    }
    if (u_gradient_opacity != 0 && c.a > 0.0)
        c.a *= gradient_opacity_weight(length(gradient_at(p)), u_gradient_low, u_gradient_high);
    if (c.a > 0.0) c.rgb = shade_sample(c.rgb, p, ray);
    if (u_shadows != 0 && c.a > 0.0) c.rgb *= shadow_at(p);
    if (u_ambient_occlusion != 0 && c.a > 0.0)
        c.rgb *= 1.0 - u_ao_strength * ambient_occlusion(p, u_ao_radius * u_min_spacing);
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
