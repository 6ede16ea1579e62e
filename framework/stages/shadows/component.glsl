// The shadows stage as a compositing component (component.cpp): the lit
// colour dimmed by the transmittance towards the light, from the light
// volume that light_volume.frag fills.
#ifndef VOXLAB_SHADOWS_COMPONENT_GLSL
#define VOXLAB_SHADOWS_COMPONENT_GLSL
#include "voxlab/ray.glsl"
#include "voxlab/lighting.glsl"
#include "shadows/shadows.glsl"

uniform sampler3D u_light_volume;  // transmittance towards the light

// The light volume's transmittance for a sample at p, read one light-volume
// voxel towards the light: a sample just under a surface would otherwise
// read the surface's own shadow, interpolated, and the depth at which each
// ray first samples the surface would show as rings ("shadow acne"). The
// shift runs along the light ray, so what shadows p shadows it still.
float shadow_at(vec3 p) {
    vec3 texel = u_volume_extent / vec3(textureSize(u_light_volume, 0));
    vec3 q = p + min(texel.x, min(texel.y, texel.z)) * light_direction();
    return filtered(u_light_volume, q / u_volume_extent).r;
}

vec4 shadows_component(vec4 c, vec3 p, Ray ray) {
    if (c.a > 0.0) c.rgb *= shadow_at(p);
    return c;
}

#endif
