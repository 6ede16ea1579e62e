// Student starter code, generated from reference/iso/iso.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
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
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return false;
}

#endif
