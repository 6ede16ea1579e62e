// Test corpus: compositing written independently of the reference (transmittance
// instead of accumulated opacity, while loops, pre-classification with the eight
// corners spelled out).
#ifndef VOXLAB_STAGE_COMPOSITE_GLSL
#define VOXLAB_STAGE_COMPOSITE_GLSL

#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"

uniform float u_early_termination;

vec4 sample_colour(vec3 p, Ray ray);

vec4 classify_post(vec3 p) {
    float value = sample_volume(p);
    vec4 colour = transfer_function(value);
    return colour;
}

vec4 weighted(ivec3 v) {
    vec4 c = transfer_function(voxel_value(v));
    c.rgb *= c.a;
    return c;
}

vec4 classify_pre(vec3 p) {
    if (u_interpolation == 0) {
        vec4 nearest = transfer_function(sample_nearest(p));
        return nearest;
    }
    vec3 x = voxel_coordinates(p) - vec3(0.5);
    ivec3 i = ivec3(floor(x));
    vec3 f = x - floor(x);
    vec4 bottom = mix(mix(weighted(i), weighted(i + ivec3(1, 0, 0)), f.x),
                      mix(weighted(i + ivec3(0, 1, 0)), weighted(i + ivec3(1, 1, 0)), f.x), f.y);
    vec4 top = mix(mix(weighted(i + ivec3(0, 0, 1)), weighted(i + ivec3(1, 0, 1)), f.x),
                   mix(weighted(i + ivec3(0, 1, 1)), weighted(i + ivec3(1, 1, 1)), f.x), f.y);
    vec4 result = mix(bottom, top, f.z);
    if (result.a <= 0.0) return vec4(0.0);
    result.rgb /= result.a;
    return result;
}

void jitter_start(inout Ray ray) {
    float shift = pixel_random() - 0.5;
    ray.t_entry = ray.t_entry + shift * u_step;
}

vec4 composite_front_to_back(Ray ray) {
    vec3 colour = vec3(0.0);
    float transmittance = 1.0;
    int m = 0;
    while (m < sample_count(ray) && 1.0 - transmittance < u_early_termination) {
        vec4 s = sample_colour(sample_position(ray, m), ray);
        float alpha = opacity_correction(s.a, u_step_units);
        colour += transmittance * alpha * s.rgb;
        transmittance *= 1.0 - alpha;
        m++;
    }
    return vec4(colour, 1.0 - transmittance);
}

vec4 composite_back_to_front(Ray ray) {
    vec3 colour = vec3(0.0);
    float opacity = 0.0;
    int m = sample_count(ray);
    while (m > 0) {
        m--;
        vec4 s = sample_colour(sample_position(ray, m), ray);
        float alpha = opacity_correction(s.a, u_step_units);
        colour = colour * (1.0 - alpha) + s.rgb * alpha;
        opacity = opacity * (1.0 - alpha) + alpha;
    }
    return vec4(colour, opacity);
}

#endif
