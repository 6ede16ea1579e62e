#version 330 core
// Probe for the function check "first_hit_random_rays": first_hit() of the
// firsthit stage on the probe's volume. Inputs: 0 the ray's origin and
// t_entry (w), 1 its direction and t_exit (w); u_step and u_threshold are
// set per case. The program is built with u_interpolation = 2 (the GPU's own
// filtering, so the check does not depend on the sampling stage) and
// u_skipping = 0 (empty-space skipping off: next_visible_sample() returns
// its argument). Result: (hit as 0 or 1, t, value).
#include "voxlab/ray.glsl"
#include "probes/probe.glsl"
#include "firsthit/firsthit.glsl"

void main() {
    Ray ray;
    ray.origin = PROBE_INPUT(0).xyz;
    ray.t_entry = PROBE_INPUT(0).w;
    ray.direction = PROBE_INPUT(1).xyz;
    ray.t_exit = PROBE_INPUT(1).w;
    float t = 0.0, value = 0.0;
    bool hit = first_hit(ray, t, value);
    probe_write(vec4(hit ? 1.0 : 0.0, t, value, 0.0), vec4(0.0));
}
