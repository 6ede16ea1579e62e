#version 330 core
// Probe for the function check "half_space_random": in_half_space() and
// clip_to_half_space() of the cutting_plane stage. Inputs: 0 the plane's
// point, 1 its normal, 2 the point tested, 3 the ray's origin and t_entry
// (w), 4 its direction and t_exit (w). Result: (inside, kept, t_entry,
// t_exit), flags as 0 or 1.
#include "voxlab/ray.glsl"
#include "probes/probe.glsl"

void main() {
    vec3 point = PROBE_INPUT(0).xyz, normal = PROBE_INPUT(1).xyz;
    bool inside = in_half_space(PROBE_INPUT(2).xyz, point, normal);
    Ray ray;
    ray.origin = PROBE_INPUT(3).xyz;
    ray.t_entry = PROBE_INPUT(3).w;
    ray.direction = PROBE_INPUT(4).xyz;
    ray.t_exit = PROBE_INPUT(4).w;
    bool kept = clip_to_half_space(ray, point, normal);
    probe_write(vec4(inside ? 1.0 : 0.0, kept ? 1.0 : 0.0, ray.t_entry, ray.t_exit), vec4(0.0));
}
