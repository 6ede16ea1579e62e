// voxlab GLSL library: reading the volume.
//
// The volume is a 3D texture over the box [0, u_volume_extent] in world
// space (voxel (i,j,k) is centred at (i+1/2, j+1/2, k+1/2) * spacing). Values
// come back in the data's own units: texel * u_value_scale + u_value_offset.
// Whether sample_volume() is nearest or trilinear is set by the scene
// ("interpolation"), through the texture's filter.
#ifndef VOXLAB_VOLUME_GLSL
#define VOXLAB_VOLUME_GLSL

uniform sampler3D u_volume;
uniform ivec3 u_volume_dims;
uniform vec3 u_volume_extent;
uniform float u_value_scale;
uniform float u_value_offset;
uniform float u_min_spacing;

// The data value at world position p.
float sample_volume(vec3 p) {
    return texture(u_volume, p / u_volume_extent).r * u_value_scale + u_value_offset;
}

// The value stored at voxel (i,j,k), clamped to the grid; no filtering.
float voxel_value(ivec3 ijk) {
    ijk = clamp(ijk, ivec3(0), u_volume_dims - 1);
    return texelFetch(u_volume, ijk, 0).r * u_value_scale + u_value_offset;
}

bool inside_volume(vec3 p) {
    return all(greaterThanEqual(p, vec3(0.0))) && all(lessThanEqual(p, u_volume_extent));
}

#endif
