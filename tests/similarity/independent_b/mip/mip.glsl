// Test corpus: MIP written independently (the obvious for loop, as most
// students write it: it is close to the reference because there is little
// else to write).
#ifndef VOXLAB_STAGE_MIP_GLSL
#define VOXLAB_STAGE_MIP_GLSL

#include "voxlab/ray.glsl"

float mip_ray(Ray ray) {
    float result = -1e30;
    for (int i = 0; i < sample_count(ray); i++) {
        result = max(result, sample_volume(sample_position(ray, i)));
    }
    return result;
}

#endif
