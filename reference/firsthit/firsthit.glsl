// Stage: first hit (closest-vessel projection).
//
// MIP loses depth: a bright vessel behind another looks the same as one in
// front. Closest-vessel projection (Zuiderveld et al., 1995) shows instead
// the first sample along the ray whose value reaches a threshold, so nearer
// structures hide farther ones. The renderer shows the value found, or its
// depth.
//
// Walk the samples m = 0, 1, ... in order and stop at the first with
// value >= u_threshold. Its distance along the ray is
// t = ray.t_entry + (m + 1/2) * u_step (sample_position() gives the point).
#ifndef VOXLAB_STAGE_FIRSTHIT_GLSL
#define VOXLAB_STAGE_FIRSTHIT_GLSL

#include "voxlab/ray.glsl"

uniform float u_threshold;  // data units

// Returns true when a sample reaches the threshold, with its distance along
// the ray (t, world units) and its value.
bool first_hit(Ray ray, out float t, out float value) {
    // BEGIN SOLUTION
    int n = sample_count(ray);
    for (int m = 0; m < n; ++m) {
        vec3 p = sample_position(ray, m);
        float v = sample_volume(p);
        if (v >= u_threshold) {
            t = ray.t_entry + (float(m) + 0.5) * u_step;
            value = v;
            return true;
        }
    }
    t = 0.0;
    value = 0.0;
    return false;
    // END SOLUTION
}

#endif
