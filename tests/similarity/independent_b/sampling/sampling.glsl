// Test corpus: sampling written independently (interpolate a z pair first, one
// helper for a line of two voxels, lerps written out by hand).
#ifndef VOXLAB_STAGE_SAMPLING_GLSL
#define VOXLAB_STAGE_SAMPLING_GLSL

#include "voxlab/volume.glsl"

float sample_nearest(vec3 p) {
    ivec3 index = ivec3(voxel_coordinates(p));  // coordinates are positive inside the volume
    vec3 c = voxel_coordinates(p);
    if (c.x < 0.0) index.x = -1;
    if (c.y < 0.0) index.y = -1;
    if (c.z < 0.0) index.z = -1;
    return voxel_value(index);
}

float lerp_z(ivec3 at, float s) {
    float near = voxel_value(at);
    float far = voxel_value(at + ivec3(0, 0, 1));
    return near + s * (far - near);
}

float sample_trilinear(vec3 p) {
    vec3 q = voxel_coordinates(p);
    q -= vec3(0.5, 0.5, 0.5);
    vec3 corner = floor(q);
    vec3 s = q - corner;
    ivec3 at = ivec3(corner);
    float a = lerp_z(at, s.z);
    float b = lerp_z(at + ivec3(1, 0, 0), s.z);
    float c = lerp_z(at + ivec3(0, 1, 0), s.z);
    float d = lerp_z(at + ivec3(1, 1, 0), s.z);
    float front = a + s.x * (b - a);
    float back = c + s.x * (d - c);
    return front + s.y * (back - front);
}

#endif
