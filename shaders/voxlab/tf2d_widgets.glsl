// voxlab GLSL library: the scene's 2D transfer-function widgets, as the
// engine uploads them (framework/include/scene/voxlab/transfer_function_2d.h).
//   u_tf2d_count     how many widgets there are; the engine bakes it into
//                    the program as a constant, so a loop up to it unrolls
//                    (much faster on llvmpipe); read it like any uniform
//   u_tf2d_kind[i]   TF2D_TRIANGLE or TF2D_BOX
//   u_tf2d_shape[i]  triangle: (value, radius, 0, 0);
//                    box: (value lo, value hi, gradient lo, gradient hi)
//   u_tf2d_color[i]  (r, g, b, opacity per unit length)
#ifndef VOXLAB_TF2D_WIDGETS_GLSL
#define VOXLAB_TF2D_WIDGETS_GLSL

#define TF2D_MAX_WIDGETS 16
#define TF2D_TRIANGLE 0
#define TF2D_BOX 1

uniform int u_tf2d_count;
uniform int u_tf2d_kind[TF2D_MAX_WIDGETS];
uniform vec4 u_tf2d_shape[TF2D_MAX_WIDGETS];
uniform vec4 u_tf2d_color[TF2D_MAX_WIDGETS];

#endif
