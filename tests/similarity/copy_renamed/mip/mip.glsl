// Test corpus: a disguised copy of reference/mip/mip.glsl (names changed,
// comments and layout rewritten, braces added): a short stage, 48 tokens.
#ifndef VOXLAB_STAGE_MIP_GLSL
#define VOXLAB_STAGE_MIP_GLSL

#include "voxlab/ray.glsl"

float mip_ray(Ray r)
{
    float best = -3.4e38;   // below any value
    int count = sample_count(r);
    for (int k = 0; k < count; ++k)
    {
        best = max(best, sample_volume(sample_position(r, k)));
    }
    return best;
}

#endif
