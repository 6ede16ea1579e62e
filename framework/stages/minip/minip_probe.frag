#version 330 core
// Probe for the function check "minip_random_rays": minip_ray() of the minip
// stage on the probe's volume. Inputs: 0 the ray's origin and t_entry (w),
// 1 its direction and t_exit (w); u_step is set per case. Built like the
// other ray probes (first_hit_probe.frag): the GPU's filtering, skipping off.
// Result: (value, 0, 0, 0).
#include "voxlab/ray.glsl"
#include "probes/probe.glsl"
#include "minip/minip.glsl"

void main() {
    Ray ray;
    ray.origin = PROBE_INPUT(0).xyz;
    ray.t_entry = PROBE_INPUT(0).w;
    ray.direction = PROBE_INPUT(1).xyz;
    ray.t_exit = PROBE_INPUT(1).w;
    probe_write(vec4(minip_ray(ray), 0.0, 0.0, 0.0), vec4(0.0));
}
