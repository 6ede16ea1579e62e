#version 330 core
// Renderer "shearwarp", one slice pass: every pixel (u, w) of the
// intermediate image reads slice u_slice where the sheared ray crosses it,
// at voxel coordinates (u, w) - u_shear (slice + 1/2) - u_offset of the
// slice (shear_warp.h), classifies the value, corrects its opacity for the
// distance between slices along the ray, and lays it under what the pixel
// gathered from the slices in front (the shearwarp stage,
// shearwarp/shearwarp.glsl). The slice is read from the slice stack (a 2D
// array texture, one layer per voxel layer): the voxel itself with nearest
// interpolation, else bilinearly within the slice, the one resampling
// shear-warp does.
#include "voxlab/volume.glsl"
#include "voxlab/classify.glsl"
#include "shearwarp/shearwarp.glsl"

uniform sampler2DArray u_stack;
uniform sampler2D u_accumulated;
uniform int u_stack_axis;
uniform int u_slice;
uniform vec2 u_shear;
uniform vec2 u_offset;
uniform float u_slice_units;  // unit lengths between slices along a ray

out vec4 frag_color;

void main() {
    vec4 accumulated = texelFetch(u_accumulated, ivec2(gl_FragCoord.xy), 0);
    int a = (u_stack_axis + 1) % 3, b = (u_stack_axis + 2) % 3;
    vec2 size = vec2(u_volume_dims[a], u_volume_dims[b]);
    vec2 x = gl_FragCoord.xy - u_shear * (float(u_slice) + 0.5) - u_offset;
    vec4 slice = vec4(0.0);  // (GLSL ES reserves the word `sample`)
    if (all(greaterThanEqual(x, vec2(0.0))) && all(lessThan(x, size))) {
        float value = u_interpolation == 0 ? texelFetch(u_stack, ivec3(ivec2(floor(x)), u_slice), 0).r
                                           : filtered(u_stack, vec3(x / size, float(u_slice))).r;
        vec4 c = transfer_function(value);
        float alpha = opacity_correction(c.a, u_slice_units);
        slice = vec4(c.rgb * alpha, alpha);
    }
    vec4 composited = shearwarp_composite(accumulated, slice);  // before the flag is read: a stub sets it
    frag_color = voxlab_not_implemented ? not_implemented_pattern() : composited;
}
