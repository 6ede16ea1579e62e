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
    // BEGIN SOLUTION
    float sum = 0.0;
    for (int i = 0; i < 14; ++i) {
        vec3 d;
        if (i < 6) {
            d = vec3(0.0);
            d[i / 2] = (i % 2 == 0) ? 1.0 : -1.0;
        } else {
            int k = i - 6;
            d = vec3((k & 1) != 0 ? 1.0 : -1.0, (k & 2) != 0 ? 1.0 : -1.0, (k & 4) != 0 ? 1.0 : -1.0) / sqrt(3.0);
        }
        vec3 q = p + radius * d;
        if (inside_volume(q)) sum += clamp(transfer_function(sample_volume(q)).a, 0.0, 1.0);
    }
    return sum / 14.0;
    // END SOLUTION
}

#endif
