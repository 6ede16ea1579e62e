// Stage: isosurface ray casting.
//
// The isosurface f(p) = u_isovalue separates values below the isovalue from
// values above it. March along the ray: the surface lies between two
// consecutive samples whose values are on different sides of the isovalue
// (f - iso changes sign, either way; a value equal to the isovalue counts as
// above). Report the later sample's position, or better,
// refine it: bisection halves the interval [t_before, t_after] that holds
// the crossing, u_refinement_steps times, keeping the half in which the sign
// still changes, and returns the middle of the last interval. Each step
// halves the error; with none it is up to one step.
//
// When the very first sample is already at or above the isovalue, the ray
// starts inside the surface (the volume is cut open there: its box, the
// region of interest or a cutting plane): report that first sample.
#ifndef VOXLAB_STAGE_ISO_GLSL
#define VOXLAB_STAGE_ISO_GLSL

#include "voxlab/ray.glsl"

uniform float u_isovalue;        // data units
uniform int u_refinement_steps;  // bisection steps

// The world position at distance t along the ray.
vec3 point_at(Ray ray, float t) {
    return ray.origin + t * ray.direction;
}

// Returns true when the ray meets the isosurface, with the distance t of the
// hit along the ray.
bool iso_hit(Ray ray, out float t) {
    // BEGIN SOLUTION
    int n = sample_count(ray);
    float t_before = 0.0;
    float before = 0.0;
    for (int m = 0; m < n; ++m) {
        float t_now = ray.t_entry + (float(m) + 0.5) * u_step;
        float now = sample_volume(sample_position(ray, m)) - u_isovalue;
        if (m == 0 && now >= 0.0) {
            t = t_now;
            return true;
        }
        if (m > 0 && (before < 0.0) != (now < 0.0)) {
            float lo = t_before, hi = t_now;
            float lo_value = before;
            for (int k = 0; k < u_refinement_steps; ++k) {
                float mid = 0.5 * (lo + hi);
                float v = sample_volume(point_at(ray, mid)) - u_isovalue;
                if ((v < 0.0) == (lo_value < 0.0)) {
                    lo = mid;
                    lo_value = v;
                } else {
                    hi = mid;
                }
            }
            t = u_refinement_steps > 0 ? 0.5 * (lo + hi) : t_now;
            return true;
        }
        t_before = t_now;
        before = now;
    }
    t = 0.0;
    return false;
    // END SOLUTION
}

#endif
