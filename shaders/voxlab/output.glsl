// voxlab GLSL library: a pixel's final colour.
//
// Renderers compute a premultiplied colour (rgb already multiplied by its
// opacity a) and hand it to finish(). Normally it is laid over the
// background: rgb + (1 - a) * background, opaque. While a cutting plane is
// drawn, each half is rendered as a layer (u_layer = 1): the premultiplied
// colour is kept as it is, and the framework lays the two halves over each
// other and over the background afterwards (shaders/voxlab/cut_compose.frag).
#ifndef VOXLAB_OUTPUT_GLSL
#define VOXLAB_OUTPUT_GLSL

#include "voxlab/not_implemented.glsl"
#include "voxlab/sample_counter.glsl"
#include "voxlab/bricks.glsl"
#include "voxlab/profile.glsl"

uniform vec3 u_background;
uniform int u_layer;

vec4 finish(vec4 premultiplied) {
    // (A bricked render adds each brick's count up by blending.)
    if (u_count_samples != 0) return vec4(float(voxlab_samples_taken), 0.0, 0.0, 1.0);
    if (u_report_stubs != 0) return stubs_reached_pixel();
    if (voxlab_not_implemented) return not_implemented_pattern();
    if (u_bricked != 0) return brick_result(premultiplied, voxlab_brick_samples);  // voxlab/bricks.glsl
    if (u_layer != 0 || u_profile != 0) return premultiplied;
    return vec4(premultiplied.rgb + (1.0 - premultiplied.a) * u_background, 1.0);
}

// A pixel whose ray sees nothing (in a bricked pass: nothing in this
// brick, so the state of the bricks in front passes on).
vec4 nothing() {
    if (u_bricked != 0 && u_count_samples == 0) return brick_state();
    return finish(vec4(0.0));
}

#endif
