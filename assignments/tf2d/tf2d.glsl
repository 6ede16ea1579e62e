// Student starter code, generated from reference/tf2d/tf2d.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: the 2D transfer function over (value, gradient magnitude).
//
// Classify a sample by its value f and its gradient magnitude g (data units
// per unit length, see gradients.h) with the scene's widgets
// (framework/include/scene/voxlab/transfer_function_2d.h has the formulas):
//  - triangle i (Levoy 1988): fv = u_tf2d_shape[i].x, radius r = shape.y,
//    opacity av = u_tf2d_color[i].a:
//        alpha = av                          if g == 0 and f == fv
//              = av (1 - |fv - f| / (r g))   if g > 0 and |fv - f| <= r g
//              = 0                           otherwise;
//  - box i: opacity u_tf2d_color[i].a where shape.x <= f <= shape.y and
//    shape.z <= g <= shape.w, else 0.
// Combine the widgets as layers: opacity 1 - prod(1 - alpha_i), colour the
// alpha-weighted mean of their colours (u_tf2d_color[i].rgb). Where no
// widget gives any opacity, return vec4(0). (Gradient magnitudes are never
// negative, so "g == 0" above can be tested as g <= 0.)
#ifndef VOXLAB_STAGE_TF2D_GLSL
#define VOXLAB_STAGE_TF2D_GLSL

#include "voxlab/tf2d_widgets.glsl"

// Colour (rgb) and opacity per unit length (a).
vec4 tf2d_classify(float f, float g) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

#endif
