#version 330 core
// voxlab: lays the two halves of a cutting-plane view over each other.
//
// Each half was rendered as a layer (premultiplied colour and opacity,
// see output.glsl) into u_layer_positive (the side the normal points into)
// and u_layer_negative. Along a ray the half that contains the ray's entry
// into the region of interest lies in front; the front layer goes over the
// back one, F + (1 - F.a) B, and the result over the background.
#include "voxlab/ray.glsl"

uniform sampler2D u_layer_positive;
uniform sampler2D u_layer_negative;
uniform vec3 u_background;

out vec4 frag_color;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 positive = texelFetch(u_layer_positive, pixel, 0);
    vec4 negative = texelFetch(u_layer_negative, pixel, 0);
    Ray ray = camera_ray();
    bool positive_in_front = true;
    if (clip_ray(ray, u_roi_min, u_roi_max))
        positive_in_front = dot(ray.origin + ray.t_entry * ray.direction - u_clip_point, u_clip_normal) >= 0.0;
    vec4 front = positive_in_front ? positive : negative;
    vec4 back = positive_in_front ? negative : positive;
    vec4 c = front + (1.0 - front.a) * back;
    frag_color = vec4(c.rgb + (1.0 - c.a) * u_background, 1.0);
}
