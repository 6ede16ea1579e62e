#version 330 core
// Renderer "splat": one pixel of one voxel's splat. Its distance from the
// splat's centre across the view, r (world units, interpolated over the
// splat's square), gives the footprint and the opacity
// (the splat stage, splat/splat.glsl) of the voxel's colour from the 1D
// transfer function; splats are blended over each other back to front.
// The footprint is cut at u_splat_cutoff standard deviations: at 3, the
// part left out is exp(-4.5) = 1.1% of the voxel's matter.
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "splat/splat.glsl"

uniform float u_splat_sigma;
uniform float u_splat_cutoff;
uniform float u_voxel_volume;  // world units cubed

in float v_value;
in vec2 v_offset;
in vec3 v_centre;
out vec4 frag_color;

void main() {
    float r = length(v_offset);
    if (r > u_splat_cutoff * u_splat_sigma || !inside_region(v_centre)) discard;
    vec4 c = transfer_function(v_value);
    float a = splat_opacity(c.a, splat_footprint(r, u_splat_sigma), u_voxel_volume);
    frag_color = voxlab_not_implemented || u_report_stubs != 0 ? not_implemented_pattern() : vec4(c.rgb * a, a);
}
