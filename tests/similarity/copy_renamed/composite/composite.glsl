// composite.glsl (test corpus: a disguised copy of reference/composite/composite.glsl:
// names changed, comments rewritten, the two compositing loops swapped, independent
// statements reordered, braces and blank lines added).
#ifndef VOXLAB_STAGE_COMPOSITE_GLSL
#define VOXLAB_STAGE_COMPOSITE_GLSL

#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"

uniform float u_early_termination;

vec4 sample_colour(vec3 p, Ray ray);

vec4 classify_post(vec3 pt) {
    return transfer_function(sample_volume(pt));   // classify after interpolating
}

vec4 classify_pre(vec3 pt) {
    if (u_interpolation == 0) {
        return transfer_function(sample_nearest(pt));
    }
    vec3 g = voxel_coordinates(pt) - 0.5;
    vec3 g0 = floor(g);
    ivec3 base = ivec3(g0);
    vec3 fr = g - g0;
    vec4 acc = vec4(0.0);
    for (int k = 0; k < 8; ++k) {
        ivec3 off = ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        vec4 col = transfer_function(voxel_value(base + off));
        vec3 wt = mix(1.0 - fr, fr, vec3(off));
        acc += wt.x * wt.y * wt.z * vec4(col.rgb * col.a, col.a);
    }
    return acc.a > 0.0 ? vec4(acc.rgb / acc.a, acc.a) : vec4(0.0);
}

void jitter_start(inout Ray r) {
    r.t_entry += (pixel_random() - 0.5) * u_step;
}

// back to front: lay each sample over what is behind it
vec4 composite_back_to_front(Ray r) {
    vec4 acc = vec4(0.0);
    for (int s = sample_count(r) - 1; s >= 0; --s) {
        vec4 col = sample_colour(sample_position(r, s), r);
        float alpha = opacity_correction(col.a, u_step_units);
        acc.a = alpha + (1.0 - alpha) * acc.a;
        acc.rgb = alpha * col.rgb + (1.0 - alpha) * acc.rgb;
    }
    return acc;
}

// front to back with early termination
vec4 composite_front_to_back(Ray r) {
    int count = sample_count(r);
    vec4 acc = vec4(0.0);
    for (int s = 0; s < count; ++s) {
        vec4 col = sample_colour(sample_position(r, s), r);
        float alpha = opacity_correction(col.a, u_step_units);
        acc.rgb += (1.0 - acc.a) * alpha * col.rgb;
        acc.a += (1.0 - acc.a) * alpha;
        if (acc.a >= u_early_termination) {
            break;
        }
    }
    return acc;
}

#endif
