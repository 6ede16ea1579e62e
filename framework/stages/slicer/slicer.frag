#version 330 core
// Renderer "slicer": one plane through the volume, perpendicular to the
// view. The stage itself, slice_plane_hit(), is in slicer/slicer.glsl.
#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"
#include "voxlab/gradients.glsl"
#include "slicer/slicer.glsl"

uniform int u_gradient;  // show |grad f| instead of f

out vec4 frag_color;

void main() {
    Ray ray = camera_ray();
    vec3 p;
    if (!slice_plane_hit(ray, p) || !inside_region(p) || !point_in_this_brick(p)) {
        frag_color = nothing();
        return;
    }
    frag_color = finish(display_value(u_gradient != 0 ? length(gradient_at(p)) : sample_volume(p)));
}
