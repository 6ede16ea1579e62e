// Student starter code, generated from reference/shearwarp/shearwarp.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: shear-warp, compositing one slice into the intermediate image. (The
// factorisation of the view is the C++ half: shear_warp.cpp.)
//
// The slices perpendicular to the principal axis are composited front to
// back, one pass each: every pixel of the intermediate image holds what its
// ray has gathered so far, `accumulated` (colour premultiplied by opacity,
// and opacity), and the slice adds its own sample behind it, `sample`
// (premultiplied too: its opacity already corrected for the distance
// between slices along the ray). In front-to-back order the new sample is
// seen through what lies in front of it ("under"):
//     C = C_acc + (1 - A_acc) C_sample,   A = A_acc + (1 - A_acc) A_sample.
// The framework reads `accumulated` from the last pass's image and writes
// the result into the next one (two images, swapped each slice).
#ifndef VOXLAB_STAGE_SHEARWARP_GLSL
#define VOXLAB_STAGE_SHEARWARP_GLSL

// What the pixel holds after this slice: the slice's sample `slice` laid
// under `accumulated` (GLSL ES reserves the word `sample`: the page's
// shaders could not use it).
vec4 shearwarp_composite(vec4 accumulated, vec4 slice) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

#endif
