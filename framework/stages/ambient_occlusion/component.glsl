// The ambient_occlusion stage as a compositing component (component.cpp):
// the lit colour darkened by the mean opacity within u_ao_radius smallest
// spacings, by up to u_ao_strength.
#ifndef VOXLAB_AMBIENT_OCCLUSION_COMPONENT_GLSL
#define VOXLAB_AMBIENT_OCCLUSION_COMPONENT_GLSL
#include "voxlab/ray.glsl"
#include "ambient_occlusion/ambient_occlusion.glsl"

uniform float u_ao_radius;
uniform float u_ao_strength;

vec4 ambient_occlusion_component(vec4 c, vec3 p, Ray ray) {
    if (c.a > 0.0) c.rgb *= 1.0 - u_ao_strength * ambient_occlusion(p, u_ao_radius * u_min_spacing);
    return c;
}

#endif
