// Student starter code, generated from reference/slicer/slicer.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: the slicer (a worked example).
//
// The slicer shows one plane of the volume: the plane perpendicular to the
// viewing direction (u_cam_forward) through the centre of the volume's box,
// moved by `offset` along the viewing direction. `offset` is in units of the
// smallest voxel spacing, so u_offset * u_min_spacing is a world distance.
//
// A point p lies on the plane when dot(p - c, n) = 0, with n the plane's
// normal (here n = u_cam_forward) and c a point on it. Along the ray
// p(t) = origin + t * direction this gives
//     t = dot(c - origin, n) / dot(direction, n).
#ifndef VOXLAB_STAGE_SLICER_GLSL
#define VOXLAB_STAGE_SLICER_GLSL

#include "voxlab/ray.glsl"

uniform float u_offset;

// Finds where the ray meets the slicing plane. Returns false when it does
// not (ray parallel to the plane, or the plane behind the ray's origin);
// otherwise stores the world position in `hit`.
bool slice_plane_hit(Ray ray, out vec3 hit) {
    // BEGIN WORKED EXAMPLE
    vec3 normal = u_cam_forward;
    vec3 centre = 0.5 * u_volume_extent + u_offset * u_min_spacing * normal;
    float denom = dot(ray.direction, normal);
    hit = vec3(0.0);
    if (abs(denom) < 1e-8) return false;
    float t = dot(centre - ray.origin, normal) / denom;
    if (t < 0.0) return false;
    hit = ray.origin + t * ray.direction;
    return true;
    // END WORKED EXAMPLE
}

#endif
