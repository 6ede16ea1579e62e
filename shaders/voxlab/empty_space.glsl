// voxlab GLSL library: empty-space skipping (framework/include/render/voxlab/empty_space.h).
//
// The volume is cut into bricks; texel b of u_bricks holds, for brick b,
// (smallest value, largest value, visible, 0): the range of every value a
// sample in the brick can read, and whether the current
// transfer function, isovalue or threshold can make any of them count.
//
// A ray walks from sample to sample as usual, but when a sample lies in an
// empty brick it leaps to the first sample past the brick's far side (where
// the ray leaves the brick's box: the nearest of its three exit planes).
// Samples keep their places, t_entry + (m + 1/2) * u_step, so an image with
// skipping is the image without it: only samples that could not count are
// left out.
//
//   next_visible_sample(ray, m)   the first sample >= m in a visible brick
//   samples_per_brick()           how many samples to take in a row before
//                                 asking again (about one brick's length)
//   last_visible_sample(ray, m)   the last sample <= m in a visible brick, or -1
//   next_sample_above(ray, m, v)  the first sample >= m in a brick whose
//                                 largest value is above v (MIP)
//   next_sample_below(ray, m, v)  the same for the smallest value below v (MinIP)
//
// All return the sample unchanged when skipping is off (u_skipping == 0:
// the scene's "skip_empty_space": false, and always while grading, so that
// a submission is rendered sample for sample). The stages never call them:
// voxlab/runs.glsl walks the ray and hands a stage's loop one run at a time.
#ifndef VOXLAB_EMPTY_SPACE_GLSL
#define VOXLAB_EMPTY_SPACE_GLSL

uniform int u_skipping;
uniform sampler3D u_bricks;
uniform vec3 u_brick_extent;  // world size of one brick
uniform ivec3 u_brick_count;

#define VOXLAB_BRICK_VISIBLE 0
#define VOXLAB_BRICK_ABOVE 1
#define VOXLAB_BRICK_BELOW 2

ivec3 brick_at(vec3 p) {
    return clamp(ivec3(floor(p / u_brick_extent)), ivec3(0), u_brick_count - 1);
}

// Where the ray enters brick b (x) and leaves it (y): the farthest of the
// box's near planes and the nearest of its far planes.
vec2 brick_span(Ray ray, ivec3 b) {
    vec3 d = ray.direction;
    vec3 safe = mix(d, vec3(1e-20), equal(d, vec3(0.0)));
    vec3 lo = vec3(b) * u_brick_extent;
    vec3 t0 = (lo - ray.origin) / safe;
    vec3 t1 = (lo + u_brick_extent - ray.origin) / safe;
    vec3 near = min(t0, t1), far = max(t0, t1);
    return vec2(max(max(near.x, near.y), near.z), min(min(far.x, far.y), far.z));
}

bool brick_counts(ivec3 b, int test, float value) {
    vec4 brick = texelFetch(u_bricks, b, 0);
    if (test == VOXLAB_BRICK_ABOVE) return brick.g > value;
    if (test == VOXLAB_BRICK_BELOW) return brick.r < value;
    return brick.b > 0.5;
}

int skip_forward(Ray ray, int m, int test, float value) {
    if (u_skipping == 0) return m;
    int n = sample_count(ray);
    while (m < n) {
        ivec3 b = brick_at(sample_location(ray, m));
        if (brick_counts(b, test, value)) return m;
        // The first sample at or past the exit: t_entry + (k + 1/2) step >= t.
        float t = brick_span(ray, b).y;
        m = max(m + 1, int(ceil((t - ray.t_entry) / u_step - 0.5)));
    }
    return n;
}

// How many samples a loop should take in a row between two calls of
// next_*_sample(): about one brick's length along the ray (at least 1). On a
// SIMD rasterizer (llvmpipe, and GPUs alike) neighbouring pixels run in
// lockstep, and a lookup between every two samples would cost as much as
// the samples it saves; a fixed run keeps the lanes together and pays for
// one lookup per brick. Without skipping, a run longer than any ray.
int samples_per_brick() {
    if (u_skipping == 0) return 1 << 24;  // no lookups: the whole ray in one run
    vec3 e = u_brick_extent;
    return max(1, int(min(min(e.x, e.y), e.z) / u_step));
}

int next_visible_sample(Ray ray, int m) {
    return skip_forward(ray, m, VOXLAB_BRICK_VISIBLE, 0.0);
}

int next_sample_above(Ray ray, int m, float value) {
    return skip_forward(ray, m, VOXLAB_BRICK_ABOVE, value);
}

int next_sample_below(Ray ray, int m, float value) {
    return skip_forward(ray, m, VOXLAB_BRICK_BELOW, value);
}

int last_visible_sample(Ray ray, int m) {
    if (u_skipping == 0) return m;
    while (m >= 0) {
        ivec3 b = brick_at(sample_location(ray, m));
        if (brick_counts(b, VOXLAB_BRICK_VISIBLE, 0.0)) return m;
        // The last sample at or before the entry: t_entry + (k + 1/2) step <= t.
        float t = brick_span(ray, b).x;
        m = min(m - 1, int(floor((t - ray.t_entry) / u_step - 0.5)));
    }
    return -1;
}

#endif
