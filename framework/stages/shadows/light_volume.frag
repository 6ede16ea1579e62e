#version 330 core
// The light volume (the shadows stage): texel (i, j, layer) holds the
// transmittance from its centre, world position (i + 1/2, j + 1/2,
// layer + 1/2) * extent / size, towards the light, computed by the stage's
// light_transmittance() with one texel's smallest size as the step.
#include "voxlab/classify.glsl"
#include "voxlab/lighting.glsl"
#include "shadows/shadows.glsl"

uniform ivec3 u_precompute_size;
uniform int u_precompute_layer;
out vec4 frag_color;

void main() {
    vec3 texel = u_volume_extent / vec3(u_precompute_size);
    vec3 p = vec3(gl_FragCoord.xy, float(u_precompute_layer) + 0.5) * texel;
    float step = min(texel.x, min(texel.y, texel.z));
    frag_color = vec4(light_transmittance(p, light_direction(), step), 0.0, 0.0, 1.0);
}
