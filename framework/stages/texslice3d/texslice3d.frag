#version 330 core
// Renderer "texslice3d": one fragment of a view-aligned slice through the 3D
// texture. The slices (the proxy geometry, reference/texslice3d/
// proxy_geometry.cpp) are u_step apart along the view direction, so a ray
// crosses them u_step / dot(d, forward) apart: the opacity is corrected for
// that length. Trilinear sampling, post-classification and optional
// shading are the ray caster's; blending composites back to front.
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/lighting.glsl"

uniform int u_outline;

in vec3 v_world;
out vec4 frag_color;

void main() {
    if (u_outline != 0) {
        frag_color = 0.5 * vec4(1.0, 0.8, 0.2, 1.0);  // translucent, premultiplied
        return;
    }
    if (!inside_region(v_world)) discard;
    Ray ray;
    ray.origin = u_cam_position;
    ray.direction = u_orthographic != 0 ? u_cam_forward : normalize(v_world - u_cam_position);
    vec4 c = transfer_function(sample_volume(v_world));
    if (c.a > 0.0) c.rgb = shade_sample(c.rgb, v_world, ray);
    float a = opacity_correction(c.a, u_step_units / max(dot(ray.direction, u_cam_forward), 1e-6));
    frag_color = voxlab_not_implemented || u_report_stubs != 0 ? not_implemented_pattern() : vec4(c.rgb * a, a);
}
