// voxlab GLSL library: linear filtering that gives the same result on every
// OpenGL.
//
// GL_LINEAR filtering is the texture unit's, and its precision is the
// implementation's: NVIDIA's GPUs weigh texels in fixed point with 8 bits
// below the texel (so a float texture's values can move by 1/512 of the
// step between texels), llvmpipe in float, and Mesa's softpipe misplaces
// samples whose coordinates fall exactly on a texel's edge. A verdict must
// not depend on which one ran, so the grader (and the function checks'
// probes) bake u_exact_filtering = 1 into every program, and then
// filtered() below reads the neighbouring texels with texelFetch and blends
// them in float arithmetic: GL_LINEAR with clamp-to-edge, written out. The
// viewer leaves it 0 and lets the texture unit filter, which is faster.
//
// Stage code that reads a table or a precomputed volume between its texels
// calls filtered() instead of texture().
#ifndef VOXLAB_FILTERING_GLSL
#define VOXLAB_FILTERING_GLSL

uniform int u_exact_filtering;

// Texel coordinates of tc (0..1 across the texture) and their weights: the
// two texels around tc on each axis, clamped to the texture (clamp to edge).
void linear_taps(vec3 tc, ivec3 size, out ivec3 lo, out ivec3 hi, out vec3 w) {
    vec3 x = tc * vec3(size) - 0.5;
    vec3 below = floor(x);
    w = x - below;
    lo = clamp(ivec3(below), ivec3(0), size - 1);
    hi = clamp(ivec3(below) + 1, ivec3(0), size - 1);
}

vec4 filtered(sampler3D t, vec3 tc) {
    if (u_exact_filtering == 0) return textureLod(t, tc, 0.0);
    ivec3 lo, hi;
    vec3 w;
    linear_taps(tc, textureSize(t, 0), lo, hi, w);
    vec4 x00 = mix(texelFetch(t, lo, 0), texelFetch(t, ivec3(hi.x, lo.y, lo.z), 0), w.x);
    vec4 x10 = mix(texelFetch(t, ivec3(lo.x, hi.y, lo.z), 0), texelFetch(t, ivec3(hi.x, hi.y, lo.z), 0), w.x);
    vec4 x01 = mix(texelFetch(t, ivec3(lo.x, lo.y, hi.z), 0), texelFetch(t, ivec3(hi.x, lo.y, hi.z), 0), w.x);
    vec4 x11 = mix(texelFetch(t, ivec3(lo.x, hi.y, hi.z), 0), texelFetch(t, hi, 0), w.x);
    return mix(mix(x00, x10, w.y), mix(x01, x11, w.y), w.z);
}

vec4 filtered(sampler2D t, vec2 tc) {
    if (u_exact_filtering == 0) return textureLod(t, tc, 0.0);
    ivec3 lo, hi;
    vec3 w;
    linear_taps(vec3(tc, 0.5), ivec3(textureSize(t, 0), 1), lo, hi, w);
    vec4 y0 = mix(texelFetch(t, lo.xy, 0), texelFetch(t, ivec2(hi.x, lo.y), 0), w.x);
    vec4 y1 = mix(texelFetch(t, ivec2(lo.x, hi.y), 0), texelFetch(t, hi.xy, 0), w.x);
    return mix(y0, y1, w.y);
}

// A layer of a 2D array texture, filtered within the layer (as texture()
// does with a whole layer number).
vec4 filtered(sampler2DArray t, vec3 tc) {
    if (u_exact_filtering == 0) return textureLod(t, tc, 0.0);
    ivec3 size = textureSize(t, 0);
    int layer = clamp(int(floor(tc.z + 0.5)), 0, size.z - 1);
    ivec3 lo, hi;
    vec3 w;
    linear_taps(vec3(tc.xy, 0.5), ivec3(size.xy, 1), lo, hi, w);
    vec4 y0 = mix(texelFetch(t, ivec3(lo.x, lo.y, layer), 0), texelFetch(t, ivec3(hi.x, lo.y, layer), 0), w.x);
    vec4 y1 = mix(texelFetch(t, ivec3(lo.x, hi.y, layer), 0), texelFetch(t, ivec3(hi.x, hi.y, layer), 0), w.x);
    return mix(y0, y1, w.y);
}

#endif
