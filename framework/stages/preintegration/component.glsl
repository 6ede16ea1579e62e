// The preintegration stage as a compositing component (component.cpp): the
// sample classified as the segment to the next one, from the table that
// preintegration_table.frag fills (u_preintegration_table).
#ifndef VOXLAB_PREINTEGRATION_COMPONENT_GLSL
#define VOXLAB_PREINTEGRATION_COMPONENT_GLSL
#include "voxlab/ray.glsl"
#include "preintegration/preintegration.glsl"

vec4 preintegration_component(vec4 c, vec3 p, Ray ray) {
    return classify_preintegrated(p, ray);
}

#endif
