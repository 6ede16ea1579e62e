// voxlab GLSL library: shading a sample with its gradient.
//
// The surface normal at a sample is the direction in which the value falls
// fastest, n = -grad f / |grad f|, which points out of bright structures.
// Volume data has no inside or outside, so lighting is two-sided: n is
// flipped when it faces away from the viewer. Where |grad f| is below
// u_min_gradient (a fraction of the value range, per unit length) the
// normal is noise and the sample keeps its unlit colour.
//
// The light is directional. Its direction is the viewing direction turned
// by u_light_azimuth (degrees, towards the image's right) and
// u_light_elevation (degrees, towards the image's top); (0, 0) is a
// headlight, shining along the view.
//
// The lighting model itself (Phong or Blinn-Phong) is the "shading" stage,
// shading/shading.glsl.
#ifndef VOXLAB_LIGHTING_GLSL
#define VOXLAB_LIGHTING_GLSL

#include "voxlab/ray.glsl"
#include "voxlab/gradients.glsl"
#include "shading/shading.glsl"

uniform int u_shading;
uniform float u_light_azimuth;
uniform float u_light_elevation;
uniform float u_min_gradient;

// Unit vector from a sample towards the light.
vec3 light_direction() {
    float az = radians(u_light_azimuth), el = radians(u_light_elevation);
    vec3 towards = -u_cam_forward * (cos(az) * cos(el)) + u_cam_right * (sin(az) * cos(el)) -
                   u_cam_down * sin(el);
    return normalize(towards);
}

// The colour of a sample with gradient g seen along `ray`, lit when shading
// is on (a renderer classifying in 2D has g at hand: it classifies by its length).
vec3 shade_sample_with_gradient(vec3 colour, vec3 g, Ray ray) {
    if (u_shading == 0) return colour;
    float g_len = length(g);
    if (g_len <= u_min_gradient * (u_value_range.y - u_value_range.x) || g_len == 0.0) return colour;
    vec3 view = -ray.direction;
    vec3 normal = -g / g_len;
    if (dot(normal, view) < 0.0) normal = -normal;
    return phong(colour, normal, light_direction(), view);
}

// The colour of a sample at p seen along `ray`, lit when shading is on.
vec3 shade_sample(vec3 colour, vec3 p, Ray ray) {
    if (u_shading == 0) return colour;
    return shade_sample_with_gradient(colour, gradient_at(p), ray);
}

#endif
