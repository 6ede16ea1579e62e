// voxlab GLSL library: one pass of a bricked render (voxlab/volume_bricks.h).
//
// A volume larger than one texture is drawn brick by brick, front to back.
// Each pass binds one brick's texture (voxlab/volume.glsl reads it through
// u_brick_origin), takes the samples of each ray that lie inside the brick,
// and adds them to the state the passes before it left in u_brick_state,
// one texel per pixel. How a brick's part is added is the renderer's
// (u_brick_combine):
//   OVER       colours composited front to back (premultiplied; the walkers
//              of voxlab/runs.glsl start from the state, so that early
//              termination sees the opacity of the bricks in front)
//   FIRST_HIT  the first brick with a hit wins: a hit is stored with 2 added
//              to its alpha, and the bricks behind it pass the state on
//   LARGEST, SMALLEST  the running maximum or minimum of the values (r) and
//              how many samples there were (g: none is the background)
//   SUM        the sum of the values (r) and how many samples (g), for a mean
// A pixel whose ray has no sample in the brick passes the state on
// (nothing()). After the last brick a resolve pass turns the state into the
// image (voxlab/brick_resolve.frag). Unbricked, u_bricked is 0 and none of
// this runs.
#ifndef VOXLAB_BRICKS_GLSL
#define VOXLAB_BRICKS_GLSL

#define VOXLAB_BRICK_OVER 1
#define VOXLAB_BRICK_FIRST_HIT 2
#define VOXLAB_BRICK_LARGEST 3
#define VOXLAB_BRICK_SMALLEST 4
#define VOXLAB_BRICK_SUM 5

uniform int u_bricked;
uniform int u_brick_combine;
uniform ivec3 u_brick_origin;        // the voxel the brick's texture starts at
uniform ivec3 u_brick_texture_dims;  // the voxels it holds (the apron included)
uniform sampler2D u_brick_state;  // what the bricks in front left, per pixel
uniform vec3 u_brick_lo;          // the world box the brick owns, [lo, hi)
uniform vec3 u_brick_hi;

// Set by in_this_brick() (voxlab/ray.glsl): where this brick's part of the
// ray starts, counted in samples of the whole ray, and how many it has.
int voxlab_brick_first_sample = 0;
int voxlab_brick_samples = 0;

vec4 brick_state() {
    return texelFetch(u_brick_state, ivec2(gl_FragCoord.xy), 0);
}

// The state after this brick, from the pixel's result in this brick: a value
// (its first component) over `samples` samples for LARGEST, SMALLEST and
// SUM, a colour for FIRST_HIT. (OVER's walkers have added the state in
// front already.)
vec4 brick_result(vec4 result, int samples) {
    vec4 s = brick_state();
    float n = s.g + float(samples);
    if (u_brick_combine == VOXLAB_BRICK_LARGEST) return vec4(max(s.r, result.r), n, 0.0, 1.0);
    if (u_brick_combine == VOXLAB_BRICK_SMALLEST) return vec4(min(s.r, result.r), n, 0.0, 1.0);
    if (u_brick_combine == VOXLAB_BRICK_SUM) return vec4(s.r + result.r * float(samples), n, 0.0, 1.0);
    if (u_brick_combine == VOXLAB_BRICK_FIRST_HIT) return vec4(result.rgb, result.a + 2.0);
    return result;
}

// Whether world position p lies in the brick's own box (half-open; the
// volume's far faces belong to the last brick: u_brick_hi lies past them).
bool in_brick_box(vec3 p) {
    return all(greaterThanEqual(p, u_brick_lo)) && all(lessThan(p, u_brick_hi));
}

#endif
