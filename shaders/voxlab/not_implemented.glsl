// voxlab GLSL library: loud stubs for student stages.
//
// The starter code (assignments/) replaces every solution body with a call
// to not_implemented(). Any pixel whose computation called one shows a
// magenta-and-black checkerboard (finish() in output.glsl), so a missing
// stage can never pass for a dark or empty image.
#ifndef VOXLAB_NOT_IMPLEMENTED_GLSL
#define VOXLAB_NOT_IMPLEMENTED_GLSL

//
// The shader preprocessor numbers the starter code's stub calls: a stub's
// `not_implemented();` compiles as `not_implemented_at(K)`, K its number in
// the program's list (ShaderProgram::stubs). With u_report_stubs set (the
// engine's stubsReached()), a pixel writes the set of stubs it reached, as
// the bits of a float, instead of its colour: so voxlab check and the viewer
// name the functions the checkerboard stands for.
bool voxlab_not_implemented = false;
uint voxlab_stubs_reached = 0u;
uniform int u_report_stubs;

void not_implemented() {
    voxlab_not_implemented = true;
}

void not_implemented_at(int k) {
    voxlab_not_implemented = true;
    voxlab_stubs_reached |= 1u << uint(k);
}

// What a pixel writes while the stubs it reached are reported.
vec4 stubs_reached_pixel() {
    return vec4(float(voxlab_stubs_reached), 0.0, 0.0, 1.0);
}

// 8-pixel squares, magenta and black, opaque.
vec4 not_implemented_pattern() {
    if (u_report_stubs != 0) return stubs_reached_pixel();
    ivec2 square = ivec2(gl_FragCoord.xy) / 8;
    return ((square.x + square.y) & 1) == 0 ? vec4(1.0, 0.0, 1.0, 1.0) : vec4(0.0, 0.0, 0.0, 1.0);
}

#endif
