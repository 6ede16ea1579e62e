// Test corpus: compositing written independently (one helper for the "over"
// operator, for loops counting samples the other way, pre-classification as
// nested weights per axis).
#ifndef VOXLAB_STAGE_COMPOSITE_GLSL
#define VOXLAB_STAGE_COMPOSITE_GLSL

#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"

uniform float u_early_termination;

vec4 sample_colour(vec3 p, Ray ray);

vec4 classify_post(vec3 p) {
    return transfer_function(sample_volume(p));
}

vec4 classify_pre(vec3 p) {
    if (u_interpolation == 0)
        return transfer_function(sample_nearest(p));
    vec3 c = voxel_coordinates(p) - 0.5;
    ivec3 lo = ivec3(floor(c));
    vec3 t = c - vec3(lo);
    vec4 acc = vec4(0.0);
    for (int z = 0; z < 2; z++)
        for (int y = 0; y < 2; y++)
            for (int x = 0; x < 2; x++) {
                float weight = (x == 0 ? 1.0 - t.x : t.x) * (y == 0 ? 1.0 - t.y : t.y) * (z == 0 ? 1.0 - t.z : t.z);
                vec4 tf = transfer_function(voxel_value(lo + ivec3(x, y, z)));
                acc.rgb += weight * tf.a * tf.rgb;
                acc.a += weight * tf.a;
            }
    if (acc.a == 0.0)
        return vec4(0.0);
    return vec4(acc.rgb / acc.a, acc.a);
}

void jitter_start(inout Ray ray) {
    float offset = u_step * (pixel_random() - 0.5);
    ray.t_entry += offset;
}

// Premultiplied "over": front over back.
vec4 over(vec4 front, vec4 back) {
    return front + (1.0 - front.a) * back;
}

vec4 premultiplied_sample(Ray ray, int m) {
    vec4 s = sample_colour(sample_position(ray, m), ray);
    float a = opacity_correction(s.a, u_step_units);
    return vec4(s.rgb * a, a);
}

vec4 composite_front_to_back(Ray ray) {
    vec4 sum = vec4(0.0);
    int samples = sample_count(ray);
    for (int m = 0; m < samples && sum.a < u_early_termination; m++)
        sum = over(sum, premultiplied_sample(ray, m));
    return sum;
}

vec4 composite_back_to_front(Ray ray) {
    vec4 sum = vec4(0.0);
    for (int left = sample_count(ray); left > 0; left--)
        sum = over(premultiplied_sample(ray, left - 1), sum);
    return sum;
}

#endif
