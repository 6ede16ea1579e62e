#version 330 core
// Probe for the function check "iso_hit_random_rays": iso_hit() of the iso
// stage on the probe's volume. Inputs: 0 the ray's origin and t_entry (w),
// 1 its direction and t_exit (w); u_step, u_isovalue and
// u_refinement_steps are set per case. Built with u_interpolation = 2 and
// u_skipping = 0, as first_hit_probe.frag. Result: (hit as 0 or 1, t).
#include "voxlab/ray.glsl"
#include "probes/probe.glsl"
#include "iso/iso.glsl"

void main() {
    Ray ray;
    ray.origin = PROBE_INPUT(0).xyz;
    ray.t_entry = PROBE_INPUT(0).w;
    ray.direction = PROBE_INPUT(1).xyz;
    ray.t_exit = PROBE_INPUT(1).w;
    float t = 0.0;
    bool hit = iso_hit(ray, t);
    probe_write(vec4(hit ? 1.0 : 0.0, t, 0.0, 0.0), vec4(0.0));
}
