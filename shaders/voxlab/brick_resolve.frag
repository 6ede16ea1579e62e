#version 330 core
// The last pass of a bricked render (voxlab/bricks.glsl): the state the
// bricks left, one texel per pixel, made into the pixel the unbricked
// renderer would have drawn. Colours are laid over the background; a
// value (the largest, the smallest, a mean) is shown through the window or
// the transfer function as the renderer's own display_value() shows it; a
// pixel no sample reached is the background.
#include "voxlab/classify.glsl"
#include "voxlab/output.glsl"

out vec4 frag_color;

void main() {
    vec4 s = brick_state();
    if (u_count_samples != 0) {
        frag_color = vec4(s.r, 0.0, 0.0, 1.0);
    } else if (u_brick_combine == VOXLAB_BRICK_FIRST_HIT) {
        frag_color = finish(s.a >= 2.0 ? vec4(s.rgb, s.a - 2.0) : vec4(0.0));
    } else if (u_brick_combine == VOXLAB_BRICK_SUM) {
        frag_color = finish(s.g > 0.0 ? display_value(s.r / s.g) : vec4(0.0));
    } else if (u_brick_combine == VOXLAB_BRICK_LARGEST || u_brick_combine == VOXLAB_BRICK_SMALLEST) {
        frag_color = finish(s.g > 0.0 ? display_value(s.r) : vec4(0.0));
    } else {
        frag_color = finish(s);
    }
}
