// Student starter code, generated from reference/texslice2d/texslice2d.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: opacity of a slice in 2D texture slicing.
//
// Transfer-function opacity is per unit length (the smallest spacing,
// u_min_spacing). The slices of a stack are u_slice_spacing apart along
// their axis (world units), but a ray crossing them at an angle travels
// farther between two slices: u_slice_spacing / |d_a|, where d_a is the
// component of the unit ray direction along the stack's axis. Without this
// correction the image darkens or brightens as the view turns.
// opacity_correction() from voxlab/classify.glsl applies the exponent.
#ifndef VOXLAB_STAGE_TEXSLICE2D_GLSL
#define VOXLAB_STAGE_TEXSLICE2D_GLSL

#include "voxlab/classify.glsl"

uniform int u_stack_axis;
uniform float u_slice_spacing;  // world units along the stack's axis

// The opacity of one slice for a ray with unit direction `direction`.
float slice_opacity(float alpha, vec3 direction) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return 0.0;
}

#endif
