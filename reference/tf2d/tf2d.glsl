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
    // BEGIN SOLUTION
    float keep = 1.0, weight = 0.0;
    vec3 colour = vec3(0.0);
    for (int i = 0; i < u_tf2d_count; ++i) {
        vec4 shape = u_tf2d_shape[i];
        float alpha = 0.0;
        if (u_tf2d_kind[i] == TF2D_BOX) {
            bool inside = f >= shape.x && f <= shape.y && g >= shape.z && g <= shape.w;
            alpha = inside ? u_tf2d_color[i].a : 0.0;
        } else {
            float distance = abs(shape.x - f);
            if (g <= 0.0) alpha = distance == 0.0 ? u_tf2d_color[i].a : 0.0;
            else if (distance <= shape.y * g) alpha = u_tf2d_color[i].a * (1.0 - distance / (shape.y * g));
        }
        keep *= 1.0 - alpha;
        weight += alpha;
        colour += alpha * u_tf2d_color[i].rgb;
    }
    if (weight <= 0.0) return vec4(0.0);
    return vec4(colour / weight, 1.0 - keep);
    // END SOLUTION
}

#endif
