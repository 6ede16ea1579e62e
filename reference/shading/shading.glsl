// Stage: Phong and Blinn-Phong shading.
//
// A lit sample's colour is the sum of three terms (B. T. Phong, 1975):
//   ambient   ka * colour                      light from everywhere;
//   diffuse   kd * max(n.l, 0) * colour        Lambert: brightest facing the light;
//   specular  ks * max(r.v, 0)^shininess       a white highlight, r = reflect(-l, n);
//             none at all where n.l <= 0 (the light does not reach that side)
//             (Phong), or ks * max(n.h, 0)^shininess with the half vector
//             h = normalize(l + v) (Blinn-Phong, J. F. Blinn 1977: cheaper,
//             and its highlight is wider for the same exponent).
// All vectors have unit length and point away from the sample: n the normal,
// l towards the light, v towards the viewer. The framework's lighting.glsl
// finds n from the gradient and skips flat regions.
#ifndef VOXLAB_STAGE_SHADING_GLSL
#define VOXLAB_STAGE_SHADING_GLSL

uniform float u_ka;
uniform float u_kd;
uniform float u_ks;
uniform float u_shininess;
uniform int u_blinn;  // 1: Blinn-Phong's half vector instead of the reflection

vec3 phong(vec3 colour, vec3 normal, vec3 light, vec3 view) {
    // BEGIN SOLUTION
    float diffuse = max(dot(normal, light), 0.0);
    float specular;
    if (u_blinn != 0) {
        specular = max(dot(normal, normalize(light + view)), 0.0);
    } else {
        vec3 reflected = reflect(-light, normal);
        specular = max(dot(reflected, view), 0.0);
    }
    // No highlight on a side the light does not reach.
    float highlight = diffuse > 0.0 ? pow(specular, u_shininess) : 0.0;
    return (u_ka + u_kd * diffuse) * colour + vec3(u_ks * highlight);
    // END SOLUTION
}

#endif
