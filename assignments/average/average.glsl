// Student starter code, generated from reference/average/average.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: average intensity projection (an X-ray-like image).
//
// An X-ray image records how much of a beam the body absorbs along each
// line: the integral of the attenuation. Dividing by the ray's length gives
// the mean value along the ray, which keeps the image within the data range
// whatever the volume's thickness: that is what this stage shows.
//
// Take sample_count(ray) samples at sample_position(ray, m) and return their
// mean. (Equal steps make the mean of the samples approximate the integral
// divided by the length.)
#ifndef VOXLAB_STAGE_AVERAGE_GLSL
#define VOXLAB_STAGE_AVERAGE_GLSL

#include "voxlab/ray.glsl"

// Returns the mean sample value along the ray (data units); the ray has at
// least one sample.
float average_ray(Ray ray) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return 0.0;
}

#endif
