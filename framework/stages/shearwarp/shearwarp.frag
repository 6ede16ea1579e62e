#version 330 core
// Renderer "shearwarp", the warp: each image pixel finds its place (u, w) on
// the intermediate image through the inverse of the factorisation's warp
// (shear_warp.h) and reads it bilinearly: the second and last resampling.
// Outside the intermediate image there is nothing.
#include "voxlab/ray.glsl"
#include "voxlab/output.glsl"

uniform sampler2D u_intermediate;
uniform mat4 u_unwarp;           // image pixel (x, y, 0, 1) -> (u, w, 0, 1)
uniform vec2 u_intermediate_size;

out vec4 frag_color;

void main() {
    vec2 pixel = vec2(gl_FragCoord.x, u_image_size.y - gl_FragCoord.y);  // rows counted from the top
    vec2 uw = (u_unwarp * vec4(pixel, 0.0, 1.0)).xy;
    vec4 c = vec4(0.0);
    if (all(greaterThanEqual(uw, vec2(0.0))) && all(lessThanEqual(uw, u_intermediate_size)))
        c = filtered(u_intermediate, uw / u_intermediate_size);
    frag_color = finish(c);
}
