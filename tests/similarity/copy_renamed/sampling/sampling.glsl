// My sampling stage (test corpus: a disguised copy of reference/sampling/sampling.glsl,
// with names changed, comments rewritten, layout changed and independent statements
// reordered, as a student hiding a copy would do).
#ifndef VOXLAB_STAGE_SAMPLING_GLSL
#define VOXLAB_STAGE_SAMPLING_GLSL

#include "voxlab/volume.glsl"

float sample_nearest(vec3 pos)
{
    return voxel_value( ivec3( floor( voxel_coordinates(pos) ) ) );   // the cell we are in
}

/* trilinear: weights from the fractional part */
float sample_trilinear(vec3 pos)
{
    vec3 coord = voxel_coordinates(pos) - 0.5;
    vec3 base = floor(coord);
    ivec3 cell = ivec3(base);
    vec3 frac = coord - base;   // in [0,1)

    // the eight corners
    float v100 = voxel_value(cell + ivec3(1, 0, 0));
    float v000 = voxel_value(cell);
    float v110 = voxel_value(cell + ivec3(1, 1, 0));
    float v010 = voxel_value(cell + ivec3(0, 1, 0));
    float v101 = voxel_value(cell + ivec3(1, 0, 1));
    float v001 = voxel_value(cell + ivec3(0, 0, 1));
    float v111 = voxel_value(cell + ivec3(1, 1, 1));
    float v011 = voxel_value(cell + ivec3(0, 1, 1));

    // along x first
    float x0 = mix(v000, v100, frac.x);
    float x2 = mix(v001, v101, frac.x);
    float x1 = mix(v010, v110, frac.x);
    float x3 = mix(v011, v111, frac.x);

    return mix( mix(x0, x1, frac.y),
                mix(x2, x3, frac.y), frac.z );
}

#endif
