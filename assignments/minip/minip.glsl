// Student starter code, generated from reference/minip/minip.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: minimum intensity projection (MinIP).
//
// The mirror image of MIP: every pixel shows the smallest value along its
// ray. Dark structures surrounded by brighter tissue stand out, which is how
// airways are shown in lung CT. Note that air outside the body is darker
// still: crop the volume (the scene's "roi") to keep it out of the rays.
//
// As in MIP, take sample_count(ray) samples at sample_position(ray, m).
#ifndef VOXLAB_STAGE_MINIP_GLSL
#define VOXLAB_STAGE_MINIP_GLSL

#include "voxlab/ray.glsl"

// Returns the smallest sample value along the ray (data units).
float minip_ray(Ray ray) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return 0.0;
}

#endif
