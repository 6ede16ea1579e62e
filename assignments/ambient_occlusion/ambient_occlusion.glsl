// Student starter code, generated from reference/ambient_occlusion/ambient_occlusion.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: local ambient occlusion.
//
// Phong shading lights every sample as if nothing stood between it and the
// light. Inside a cavity, a crease or a bowl, much of the light from around
// a point is blocked by the material next to it, and such places look darker
// in reality. Ambient occlusion estimates how much of the surroundings is
// filled: look a short distance from the sample in many directions and take
// the mean opacity found there (the "local" occlusion of VTK's and 3D
// Slicer's volume rendering options; Zhukov, Iones and Kronin 1998 for the
// idea of obscurance within a radius).
//
// Here: the 14 directions of the 6 axes (+-x, +-y, +-z) and the 8 cube
// diagonals (+-1, +-1, +-1)/sqrt(3), each at the distance `radius` (world
// units) from p. A point outside the volume's box is empty (opacity 0); a
// point inside has the transfer function's opacity per unit length of the
// value there, clamped to [0, 1]. The occlusion is the mean of the 14:
//
//     o(p) = (1/14) sum_i clamp(transfer_function(sample_volume(q_i)).a, 0, 1)
//     q_i  = p + radius d_i
//
// The composite renderer, with `ambient_occlusion` on, multiplies each lit
// sample's colour by 1 - u_ao_strength * o(p), with radius = `ao_radius`
// smallest spacings.
#ifndef VOXLAB_STAGE_AMBIENT_OCCLUSION_GLSL
#define VOXLAB_STAGE_AMBIENT_OCCLUSION_GLSL

#include "voxlab/volume.glsl"
#include "voxlab/classify.glsl"

// The mean opacity at the 14 points `radius` (world units) around p, in [0, 1].
float ambient_occlusion(vec3 p, float radius) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return 0.0;
}

#endif
