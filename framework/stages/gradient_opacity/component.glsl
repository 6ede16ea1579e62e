// The gradient_opacity stage as a compositing component (component.cpp):
// the classified sample's opacity weighted by the ramp of its gradient
// magnitude between u_gradient_low and u_gradient_high.
#ifndef VOXLAB_GRADIENT_OPACITY_COMPONENT_GLSL
#define VOXLAB_GRADIENT_OPACITY_COMPONENT_GLSL
#include "voxlab/ray.glsl"
#include "voxlab/lighting.glsl"
#include "gradient_opacity/gradient_opacity.glsl"

uniform float u_gradient_low;
uniform float u_gradient_high;

vec4 gradient_opacity_component(vec4 c, vec3 p, Ray ray) {
    if (c.a > 0.0) c.a *= gradient_opacity_weight(length(gradient_at(p)), u_gradient_low, u_gradient_high);
    return c;
}

#endif
