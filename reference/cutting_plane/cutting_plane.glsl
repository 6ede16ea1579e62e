// Stage: the cutting plane.
//
// A plane through `point` with normal `normal` splits space into two
// half-spaces. The renderer drawing the positive side may only sample points
// p with dot(p - point, normal) >= 0; the framework draws the other side by
// calling the same function with the normal flipped, and lays the two
// halves over each other, front over back.
//
// Along the ray p(t) = origin + t * direction the signed distance to the
// plane is linear in t:
//     s(t) = dot(origin - point, normal) + t * dot(direction, normal),
// so the ray crosses the plane once, at t = -s(0) / dot(direction, normal),
// unless it runs parallel to it (then it stays on one side: keep all of it
// when s(0) >= 0, nothing otherwise). Moving towards the normal
// (dot(direction, normal) > 0) the ray enters the half-space there: raise
// t_entry. Moving away, it leaves: lower t_exit.
#ifndef VOXLAB_STAGE_CUTTING_PLANE_GLSL
#define VOXLAB_STAGE_CUTTING_PLANE_GLSL

#include "voxlab/ray.glsl"

// Whether p lies on the kept side (the plane itself included).
bool in_half_space(vec3 p, vec3 point, vec3 normal) {
    // BEGIN SOLUTION
    return dot(p - point, normal) >= 0.0;
    // END SOLUTION
}

// Shortens the ray's [t_entry, t_exit] to the part inside the half-space.
// Returns false when nothing is left.
bool clip_to_half_space(inout Ray ray, vec3 point, vec3 normal) {
    // BEGIN SOLUTION
    float along = dot(ray.direction, normal);
    float start = dot(ray.origin - point, normal);
    if (abs(along) < 1e-12) return start >= 0.0 && ray.t_exit > ray.t_entry;  // parallel
    float t = -start / along;
    if (along > 0.0) ray.t_entry = max(ray.t_entry, t);
    else ray.t_exit = min(ray.t_exit, t);
    return ray.t_exit > ray.t_entry;
    // END SOLUTION
}

#endif
