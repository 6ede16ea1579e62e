// voxlab GLSL library: loud stubs for student stages.
//
// The starter code (assignments/) replaces every solution body with a call
// to not_implemented(). Any pixel whose computation called one shows a
// magenta-and-black checkerboard (finish() in output.glsl), so a missing
// stage can never pass for a dark or empty image.
#ifndef VOXLAB_NOT_IMPLEMENTED_GLSL
#define VOXLAB_NOT_IMPLEMENTED_GLSL

bool voxlab_not_implemented = false;

void not_implemented() {
    voxlab_not_implemented = true;
}

// 8-pixel squares, magenta and black, opaque.
vec4 not_implemented_pattern() {
    ivec2 square = ivec2(gl_FragCoord.xy) / 8;
    return ((square.x + square.y) & 1) == 0 ? vec4(1.0, 0.0, 1.0, 1.0) : vec4(0.0, 0.0, 0.0, 1.0);
}

#endif
