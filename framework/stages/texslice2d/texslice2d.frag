#version 330 core
// Renderer "texslice2d": one fragment of an axis-aligned slice. The slice
// stack perpendicular to u_stack_axis is a 2D array texture (one layer per
// voxel layer, bilinear within a layer); slices between two layers blend
// them (Rezk-Salama et al. 2000). The slice's value is classified by the
// transfer function and its opacity corrected for the distance between
// slices along the ray (texslice2d/texslice2d.glsl); blending composites.
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "texslice2d/texslice2d.glsl"

uniform sampler2DArray u_stack;
uniform int u_outline;

in vec3 v_world;
out vec4 frag_color;

float stack_value(vec3 p) {
    int a = u_stack_axis, b = (a + 1) % 3, c = (a + 2) % 3;
    vec2 uv = vec2(p[b] / u_volume_extent[b], p[c] / u_volume_extent[c]);
    float layers = float(u_volume_dims[a]);
    float layer = clamp(p[a] / u_volume_extent[a] * layers - 0.5, 0.0, layers - 1.0);
    float below = floor(layer);
    float above = min(below + 1.0, layers - 1.0);
    return mix(filtered(u_stack, vec3(uv, below)).r, filtered(u_stack, vec3(uv, above)).r, layer - below);
}

void main() {
    if (u_outline != 0) {
        frag_color = 0.5 * vec4(1.0, 0.8, 0.2, 1.0);  // translucent, premultiplied
        return;
    }
    if (!inside_region(v_world)) discard;
    vec3 direction = u_orthographic != 0 ? u_cam_forward : normalize(v_world - u_cam_position);
    vec4 c = transfer_function(stack_value(v_world));
    float a = slice_opacity(c.a, direction);
    frag_color = voxlab_not_implemented || u_report_stubs != 0 ? not_implemented_pattern() : vec4(c.rgb * a, a);
}
