// Stage: thin-slab MIP.
//
// A MIP of the whole volume piles everything on top of everything. Radiology
// workstations therefore project a slab: only the part of the volume within
// thickness/2 of a plane perpendicular to the view. Moving the plane through
// the volume scrolls through it, slab by slab.
//
// The plane passes through the centre of the volume's box moved by u_offset
// along the viewing direction u_cam_forward (its normal); u_offset and
// u_thickness are in units of the smallest spacing (u_min_spacing). Clip the
// ray to the slab: the points p with |dot(p - c, u_cam_forward)| <= h, where
// c is the plane's centre and h = thickness/2 in world units: two
// half-spaces, which clip_to_half_space() from the cutting-plane stage
// handles (rays parallel to the slab included). The MIP stage (mip/mip.glsl)
// then projects what is left.
#ifndef VOXLAB_STAGE_SLAB_MIP_GLSL
#define VOXLAB_STAGE_SLAB_MIP_GLSL

#include "voxlab/ray.glsl"

uniform float u_offset;
uniform float u_thickness;

// Shortens the ray to the slab; returns false when nothing is left.
bool clip_to_slab(inout Ray ray) {
    // BEGIN SOLUTION
    vec3 n = u_cam_forward;
    vec3 centre = 0.5 * u_volume_extent + u_offset * u_min_spacing * n;
    float h = 0.5 * u_thickness * u_min_spacing;
    // Two half-spaces: in front of the far face and behind the near face.
    return clip_to_half_space(ray, centre - h * n, n) && clip_to_half_space(ray, centre + h * n, -n);
    // END SOLUTION
}

#endif
