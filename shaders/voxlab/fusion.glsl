// voxlab GLSL library: a second scalar volume fused with the first (scene
// "fusion", see Fusion in scene.h).
//
// The second volume covers the same box as the first; a grid of another
// size is read at the same place in the box, i.e. resampled onto it by its
// own voxel coordinates. It is classified by its own transfer function
// (u_tf2, the same table layout as u_tf) and read as the scene's
// interpolation says: nearest, or else trilinear by the GPU's own filtering
// (the cubic interpolations get this trilinear too; on llvmpipe an 8-bit
// second volume is filtered in 8-bit fixed point, within a grey level).
//
// classify_fused(p, first) combines the first volume's classification at p
// with the second's, both colour (rgb) and opacity per unit length (a):
//   0 checkerboard   3D squares u_fusion_checker world units wide alternate;
//   1 split          the first volume where dot(p - point, normal) >= 0;
//   2 color_opacity  colour from the second, opacity from the first;
//   3 sum            opacities added (clamped to 1), colour the
//                    opacity-weighted mean: two absorbing, emitting media
//                    in one place.
#ifndef VOXLAB_FUSION_GLSL
#define VOXLAB_FUSION_GLSL

#include "voxlab/volume.glsl"

uniform sampler3D u_volume2;
uniform ivec3 u_volume2_dims;
uniform float u_value2_scale;
uniform float u_value2_offset;
uniform sampler2D u_tf2;
uniform int u_tf2_size;
uniform vec2 u_tf2_range;
uniform int u_fusion_mode;
uniform float u_fusion_checker;
uniform vec3 u_fusion_point;
uniform vec3 u_fusion_normal;

float voxel2_value(ivec3 ijk) {
    ijk = clamp(ijk, ivec3(0), u_volume2_dims - 1);
    return texelFetch(u_volume2, ijk, 0).r * u_value2_scale + u_value2_offset;
}

float sample_volume2(vec3 p) {
    vec3 v = p / u_volume_extent * vec3(u_volume2_dims);
    if (u_interpolation == 0) return voxel2_value(ivec3(floor(v)));
    // Linear filtering by the GPU (the texture's filter is linear): a shipped
    // framework file never spells out the sampling stage's interpolation.
    return filtered(u_volume2, p / u_volume_extent).r * u_value2_scale + u_value2_offset;
}

vec4 transfer_function2(float value) {
    float f = clamp((value - u_tf2_range.x) / max(u_tf2_range.y - u_tf2_range.x, 1e-30), 0.0, 1.0);
    float x = f * float(u_tf2_size - 1);
    int i = min(int(x), max(u_tf2_size - 2, 0));
    int j = min(i + 1, u_tf2_size - 1);
    return mix(texelFetch(u_tf2, ivec2(i % 4096, i / 4096), 0), texelFetch(u_tf2, ivec2(j % 4096, j / 4096), 0),
               x - float(i));
}

vec4 classify_fused(vec3 p, vec4 first) {
    vec4 second = transfer_function2(sample_volume2(p));
    if (u_fusion_mode == 0) {
        ivec3 cell = ivec3(floor(p / u_fusion_checker));
        return ((cell.x + cell.y + cell.z) & 1) == 0 ? first : second;
    }
    if (u_fusion_mode == 1) return dot(p - u_fusion_point, u_fusion_normal) >= 0.0 ? first : second;
    if (u_fusion_mode == 2) return vec4(second.rgb, first.a);
    float total = first.a + second.a;
    vec3 colour = total > 0.0 ? (first.a * first.rgb + second.a * second.rgb) / total : vec3(0.0);
    return vec4(colour, min(total, 1.0));
}

#endif
