// voxlab GLSL library: camera rays and where to sample along them.
//
// Conventions (README, "Rendering conventions"):
//  - image pixel (px, py), py downwards, has its centre at (px+1/2, py+1/2);
//  - a ray enters the box at t_entry and leaves at t_exit;
//  - sample m sits at t_entry + (m + 1/2) * u_step, for m = 0, 1, ... while
//    it is still inside the box, so a ray of length L gets
//    floor(L / u_step + 1/2) samples;
//  - u_step is in world units (the scene's step times the smallest spacing);
//  - the region a renderer may sample is the volume's box, cropped by the
//    scene's region of interest (u_roi_min..u_roi_max, world units), by the
//    half-space each of the scene's clip planes keeps and, while a cutting
//    plane is drawn, by one half-space of that plane.
#ifndef VOXLAB_RAY_GLSL
#define VOXLAB_RAY_GLSL

#include "voxlab/volume.glsl"
#include "voxlab/sample_counter.glsl"
#include "voxlab/profile.glsl"

uniform vec3 u_cam_position;
uniform vec3 u_cam_forward;
uniform vec3 u_cam_right;
uniform vec3 u_cam_down;
uniform float u_pixel_scale;
uniform vec2 u_image_size;
uniform int u_orthographic;
uniform float u_step;        // world units
uniform float u_step_units;  // the same step in units of the smallest spacing
uniform vec3 u_roi_min;      // the region of interest (default: the box)
uniform vec3 u_roi_max;
uniform int u_clip_plane;    // 1: keep only dot(p - u_clip_point, u_clip_normal) >= 0
uniform vec3 u_clip_point;
uniform vec3 u_clip_normal;
uniform int u_clip_plane_count;  // the scene's clip planes (0..6), each keeping
uniform vec3 u_clip_plane_points[6];   // dot(p - point, normal) >= 0
uniform vec3 u_clip_plane_normals[6];

struct Ray {
    vec3 origin;
    vec3 direction;  // unit length
    float t_entry;   // where the ray enters the volume's box
    float t_exit;    // where it leaves
};

Ray voxlab_profile_ray;  // the ray sample_count() last saw (voxlab/profile.glsl)

// The ray through this fragment's pixel centre (in the ray profile's run,
// through the profiled pixel's).
Ray camera_ray() {
    // gl_FragCoord counts rows from the bottom; image rows count from the top.
    vec2 pixel = vec2(gl_FragCoord.x, u_image_size.y - gl_FragCoord.y);
    if (u_profile != 0) pixel = u_profile_pixel + 0.5;
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

// The stages' segments: the half-space tests below (clip_to_half_space,
// in_half_space) are a stage's, the one whose segment includes them.
#include "stages/*/ray_segment.glsl"

// Clips the ray to the region this renderer samples: the region of interest
// (which lies inside the volume's box), the clip planes' half-spaces and the
// cutting plane's.
bool clip_to_volume(inout Ray ray) {
    if (!clip_ray(ray, u_roi_min, u_roi_max)) return false;
    for (int i = 0; i < u_clip_plane_count; ++i)
        if (!clip_to_half_space(ray, u_clip_plane_points[i], u_clip_plane_normals[i])) return false;
    if (u_clip_plane != 0 && !clip_to_half_space(ray, u_clip_point, u_clip_normal)) return false;
    voxlab_profile_hit = true;  // the ray profile's record: the ray meets the region
    return true;
}

// Whether a point lies in that region (for renderers that do not march).
bool inside_region(vec3 p) {
    bool in_roi = all(greaterThanEqual(p, u_roi_min)) && all(lessThanEqual(p, u_roi_max));
    for (int i = 0; i < u_clip_plane_count; ++i)
        in_roi = in_roi && in_half_space(p, u_clip_plane_points[i], u_clip_plane_normals[i]);
    return in_roi && (u_clip_plane == 0 || in_half_space(p, u_clip_point, u_clip_normal));
}

// How many samples fit between t_entry and t_exit (in the ray profile's
// run, no more than this fragment's sample and the ones before it).
int sample_count(Ray ray) {
    int n = int(floor((ray.t_exit - ray.t_entry) / u_step + 0.5));
    if (u_profile == 0) return n;
    if (voxlab_profile_samples < 0) {  // the first call: the entry's primary ray
        voxlab_profile_ray = ray;
        voxlab_profile_samples = n;
    }
    return min(n, voxlab_profile_index() + 1);
}

// A bricked render (voxlab/bricks.glsl): the part of the clipped ray whose
// samples lie in this pass's brick, t_entry + (m + 1/2) * u_step in
// [where the ray enters its box, where it leaves), as sample_run() would
// cut it, so every sample keeps its place. False when there is none, or
// when a brick in front already holds the pixel's first hit. Unbricked:
// true, and the ray is left as it is.
bool in_this_brick(inout Ray ray) {
    if (u_bricked == 0) return true;
    if (u_brick_combine == VOXLAB_BRICK_FIRST_HIT && brick_state().a >= 2.0) return false;
    vec3 d = ray.direction;
    vec3 safe = mix(d, vec3(1e-20), equal(d, vec3(0.0)));
    vec3 t0 = (u_brick_lo - ray.origin) / safe;
    vec3 t1 = (u_brick_hi - ray.origin) / safe;
    vec3 near = min(t0, t1), far = max(t0, t1);
    float enter = max(max(near.x, near.y), near.z), leave = min(min(far.x, far.y), far.z);
    float n = float(sample_count(ray));
    int first = int(clamp(ceil((enter - ray.t_entry) / u_step - 0.5), 0.0, n));
    int end = int(clamp(ceil((leave - ray.t_entry) / u_step - 0.5), 0.0, n));
    voxlab_brick_first_sample = first;
    voxlab_brick_samples = max(end - first, 0);
    if (end <= first) return false;
    ray.t_exit = ray.t_entry + float(end) * u_step;
    ray.t_entry = ray.t_entry + float(first) * u_step;
    return true;
}

// The same for a single point (a slice view's): whether it is this brick's.
bool point_in_this_brick(vec3 p) {
    return u_bricked == 0 || in_brick_box(p);
}

// Where sample m lies, without counting it as taken (for the empty-space
// walk, which looks at a sample's brick before anyone samples it).
vec3 sample_location(Ray ray, int m) {
    return ray.origin + (ray.t_entry + (float(m) + 0.5) * u_step) * ray.direction;
}

// The world position of sample m.
vec3 sample_position(Ray ray, int m) {
    if (u_count_samples != 0) voxlab_samples_taken += 1;
    return sample_location(ray, m);
}

// A pseudo-random number in [0, 1) that differs from pixel to pixel and is
// the same in every frame (a hash of the pixel's coordinates), for jitter.
float pixel_random() {
    uvec2 q = uvec2(gl_FragCoord.xy);
    if (u_profile != 0) q = uvec2(u_profile_pixel.x, u_image_size.y - 1.0 - u_profile_pixel.y);
    uint h = q.x * 1973u + q.y * 9277u + 26699u;
    h = (h ^ (h >> 15)) * 2654435769u;
    h ^= h >> 13;
    h *= 1274126177u;
    h ^= h >> 16;
    return float(h >> 8) / 16777216.0;
}

// A hit distance t shown as grey: 1 where the ray enters the volume's
// bounding sphere (centre c = extent/2, radius rho = |extent|/2), 0 where it
// leaves: grey = 1 - (t - t_near) / (2 rho), t_near = dot(c - origin, d) - rho.
// The README's conventions state the same formula, so depth images can be
// turned back into distances.
float depth_grey(Ray ray, float t) {
    vec3 centre = 0.5 * u_volume_extent;
    float radius = 0.5 * length(u_volume_extent);
    float t_near = dot(centre - ray.origin, ray.direction) - radius;
    return clamp(1.0 - (t - t_near) / (2.0 * radius), 0.0, 1.0);
}

// The profile's record of this fragment's sample (voxlab/profile.glsl):
// (value, displayed value, t, samples of the whole ray); the last is -1
// when the ray missed the region, -2 when a stage is not implemented and
// -3 when the ray met the region but nothing asked sample_count().
vec4 voxlab_profile_record() {
    if (voxlab_not_implemented) return vec4(0.0, 0.0, 0.0, -2.0);
    if (voxlab_profile_samples < 0) return vec4(0.0, 0.0, 0.0, voxlab_profile_hit ? -3.0 : -1.0);
    int i = voxlab_profile_index();
    float t = voxlab_profile_ray.t_entry + (float(i) + 0.5) * u_step;
    float value = i < voxlab_profile_samples ? sample_volume(sample_location(voxlab_profile_ray, i)) : 0.0;
    return vec4(value, voxlab_profile_scalar, t, float(voxlab_profile_samples));
}

#include "voxlab/empty_space.glsl"

#endif
