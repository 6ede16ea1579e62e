// Student starter code, generated from reference/cutting_plane/cutting_plane.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
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
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return false;
}

// Shortens the ray's [t_entry, t_exit] to the part inside the half-space.
// Returns false when nothing is left.
bool clip_to_half_space(inout Ray ray, vec3 point, vec3 normal) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return false;
}

#endif
