// voxlab GLSL library: camera rays and where to sample along them.
//
// Conventions (README, "Rendering conventions"):
//  - image pixel (px, py), py downwards, has its centre at (px+1/2, py+1/2);
//  - a ray enters the box at t_entry and leaves at t_exit;
//  - sample m sits at t_entry + (m + 1/2) * u_step, for m = 0, 1, ... while
//    it is still inside the box, so a ray of length L gets
//    floor(L / u_step + 1/2) samples;
//  - u_step is in world units (the scene's step times the smallest spacing).
#ifndef VOXLAB_RAY_GLSL
#define VOXLAB_RAY_GLSL

#include "voxlab/volume.glsl"

uniform vec3 u_cam_position;
uniform vec3 u_cam_forward;
uniform vec3 u_cam_right;
uniform vec3 u_cam_down;
uniform float u_pixel_scale;
uniform vec2 u_image_size;
uniform int u_orthographic;
uniform float u_step;        // world units
uniform float u_step_units;  // the same step in units of the smallest spacing

struct Ray {
    vec3 origin;
    vec3 direction;  // unit length
    float t_entry;   // where the ray enters the volume's box
    float t_exit;    // where it leaves
};

// The ray through this fragment's pixel centre.
Ray camera_ray() {
    // gl_FragCoord counts rows from the bottom; image rows count from the top.
    vec2 pixel = vec2(gl_FragCoord.x, u_image_size.y - gl_FragCoord.y);
    vec2 uv = (pixel - 0.5 * u_image_size) * u_pixel_scale;
    Ray ray;
    if (u_orthographic != 0) {
        ray.origin = u_cam_position + uv.x * u_cam_right + uv.y * u_cam_down;
        ray.direction = u_cam_forward;
    } else {
        ray.origin = u_cam_position;
        ray.direction = normalize(u_cam_forward + uv.x * u_cam_right + uv.y * u_cam_down);
    }
    ray.t_entry = 0.0;
    ray.t_exit = -1.0;
    return ray;
}

// Clips the ray against the box [lo, hi] (the slab method: intersect the
// three pairs of parallel planes and keep the overlap). Returns false when
// the ray misses. t_entry is never behind the ray's origin.
bool clip_ray(inout Ray ray, vec3 lo, vec3 hi) {
    // Axis-parallel rays would divide by zero; a tiny direction component
    // gives huge but finite slab distances with the right signs instead.
    vec3 d = ray.direction;
    vec3 safe = mix(d, vec3(1e-20), equal(d, vec3(0.0)));
    vec3 t0 = (lo - ray.origin) / safe;
    vec3 t1 = (hi - ray.origin) / safe;
    vec3 tnear = min(t0, t1);
    vec3 tfar = max(t0, t1);
    ray.t_entry = max(max(max(tnear.x, tnear.y), tnear.z), max(ray.t_entry, 0.0));
    ray.t_exit = min(min(tfar.x, tfar.y), tfar.z);
    return ray.t_exit > ray.t_entry;
}

bool clip_to_volume(inout Ray ray) {
    return clip_ray(ray, vec3(0.0), u_volume_extent);
}

// How many samples fit between t_entry and t_exit.
int sample_count(Ray ray) {
    return int(floor((ray.t_exit - ray.t_entry) / u_step + 0.5));
}

// The world position of sample m.
vec3 sample_position(Ray ray, int m) {
    return ray.origin + (ray.t_entry + (float(m) + 0.5) * u_step) * ray.direction;
}

#endif
