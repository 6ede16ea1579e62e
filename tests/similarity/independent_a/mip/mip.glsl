// Test corpus: MIP written independently (a while loop with an if).
#ifndef VOXLAB_STAGE_MIP_GLSL
#define VOXLAB_STAGE_MIP_GLSL

#include "voxlab/ray.glsl"

float mip_ray(Ray ray) {
    int count = sample_count(ray);
    float best = sample_volume(sample_position(ray, 0));
    int k = 1;
    while (k < count) {
        float v = sample_volume(sample_position(ray, k));
        if (v > best) best = v;
        k = k + 1;
    }
    return best;
}

#endif
