// Stage: maximum intensity projection (MIP).
//
// MIP shows, for every pixel, the largest value met along its ray. It needs
// no transfer function and no ordering, which makes it the classic first
// ray caster (and the workhorse of CT angiography, where contrast-filled
// vessels are the brightest structures).
//
// The framework has already clipped the ray to the volume's box, so
// ray.t_entry and ray.t_exit are set. Take sample_count(ray) samples at
// sample_position(ray, m), m = 0, 1, ..., read each with sample_volume(p)
// and keep the maximum.
#ifndef VOXLAB_STAGE_MIP_GLSL
#define VOXLAB_STAGE_MIP_GLSL

#include "voxlab/ray.glsl"

// Returns the largest sample value along the ray (data units).
float mip_ray(Ray ray) {
    // BEGIN SOLUTION
    float maximum = -3.4e38;
    int n = sample_count(ray);
    for (int m = 0; m < n; ++m)
        maximum = max(maximum, sample_volume(sample_position(ray, m)));
    return maximum;
    // END SOLUTION
}

#endif
