// The cutting plane's segment of ray.glsl (included there by
// "stages/*/ray_segment.glsl"): the half-space tests students write in
// this stage, clip_to_half_space and in_half_space, which every renderer's
// clip planes and the cutting plane use.
#include "cutting_plane/cutting_plane.glsl"
