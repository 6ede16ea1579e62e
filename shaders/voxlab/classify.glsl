// voxlab GLSL library: turning data values into colours.
//
//  - Grey: a linear window [lo, hi] in data units maps lo to black and hi to
//    white, clamped.
//  - Colour: the scene's 1D transfer function, a table over the data range
//    [lo, hi] = u_tf_range. Entry i of the u_tf_size entries holds the
//    function at lo + i*(hi-lo)/(size-1); entries are stored row by row in a
//    2D texture (4096 per row) and interpolated here, in float.
//  - Opacity in the table is per unit length (the smallest spacing); a
//    sample that stands for u_step_units of that length has opacity
//    1 - (1 - alpha)^u_step_units.
#ifndef VOXLAB_CLASSIFY_GLSL
#define VOXLAB_CLASSIFY_GLSL

#include "voxlab/bricks.glsl"
#include "voxlab/profile.glsl"

uniform vec2 u_window;
uniform int u_has_tf;
uniform sampler2D u_tf;
uniform vec2 u_tf_range;
uniform int u_tf_size;

float apply_window(float value) {
    return clamp((value - u_window.x) / (u_window.y - u_window.x), 0.0, 1.0);
}

vec4 tf_entry(int i) {
    const int row_length = 4096;
    return texelFetch(u_tf, ivec2(i % row_length, i / row_length), 0);
}

// Colour (rgb) and opacity per unit length (a) of a data value.
vec4 transfer_function(float value) {
    float f = clamp((value - u_tf_range.x) / max(u_tf_range.y - u_tf_range.x, 1e-30), 0.0, 1.0);
    float x = f * float(u_tf_size - 1);
    int i = min(int(x), max(u_tf_size - 2, 0));
    return mix(tf_entry(i), tf_entry(min(i + 1, u_tf_size - 1)), x - float(i));
}

float opacity_correction(float alpha, float step_units) {
    return 1.0 - pow(1.0 - clamp(alpha, 0.0, 1.0), step_units);
}

// How a single value is shown by the projection renderers (a slice view, MIP,
// ...): opaque grey through the window or, when the scene has a transfer
// function, its colour with its opacity. The result is premultiplied
// (rgb already times alpha), ready for finish() in voxlab/output.glsl.
vec4 display_value(float value) {
    voxlab_profile_scalar = value;  // the ray profile's record (voxlab/profile.glsl)
    // A bricked pass keeps the value itself; the resolve pass shows it.
    if (u_bricked != 0 && u_brick_combine >= VOXLAB_BRICK_LARGEST) return vec4(value);
    if (u_has_tf == 0) return vec4(vec3(apply_window(value)), 1.0);
    vec4 c = transfer_function(value);
    return vec4(c.rgb * c.a, c.a);
}

#endif
