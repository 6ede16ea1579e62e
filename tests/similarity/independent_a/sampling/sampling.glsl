// Test corpus: sampling written independently of the reference (a loop over the
// eight corners with explicit weights, as a student who thinks of the formula
// as a sum would write it).
#ifndef VOXLAB_STAGE_SAMPLING_GLSL
#define VOXLAB_STAGE_SAMPLING_GLSL

#include "voxlab/volume.glsl"

float sample_nearest(vec3 p) {
    vec3 v = voxel_coordinates(p);
    int x = int(floor(v.x));
    int y = int(floor(v.y));
    int z = int(floor(v.z));
    return voxel_value(ivec3(x, y, z));
}

float sample_trilinear(vec3 p) {
    vec3 g = voxel_coordinates(p) - vec3(0.5);
    ivec3 base = ivec3(floor(g));
    vec3 t = fract(g);
    float total = 0.0;
    for (int dz = 0; dz <= 1; dz++) {
        float wz = dz == 1 ? t.z : 1.0 - t.z;
        for (int dy = 0; dy <= 1; dy++) {
            float wy = dy == 1 ? t.y : 1.0 - t.y;
            for (int dx = 0; dx <= 1; dx++) {
                float wx = dx == 1 ? t.x : 1.0 - t.x;
                total += wx * wy * wz * voxel_value(base + ivec3(dx, dy, dz));
            }
        }
    }
    return total;
}

#endif
