// voxlab GLSL library: the ray profile's instrumented run
// (RenderEngine::profileRay, framework/include/render/voxlab/ray_profile.h).
//
// The profile shows what the stage's own code does along one pixel's ray.
// The entry shader runs unchanged but for this: every fragment of a small
// target follows the profiled pixel's ray (u_profile_pixel), and fragment i
// sees that ray cut after its sample i: sample_count() gives at most i + 1.
// A stage's loop over the ray then computes, in fragment i, the pixel it
// would give if the ray ended after sample i: the accumulated colour of
// compositing, the running maximum of MIP, the first hit so far. The first
// pass keeps each fragment's colour (u_profile = 1; finish() returns it
// premultiplied, before the background); the second (u_profile = 2) also
// records, in place of the colour, sample i's value as the sampling stage
// reads it, the value the entry shader last displayed (MIP's running
// maximum: display_value's argument), where sample i lies along the ray and
// how many samples the whole ray has (voxlab_profile_record(), written by a
// main() that calls the entry shader's own: shader.cpp). The ray recorded is
// the first sample_count() sees, the entry shader's own. Nothing of this is
// compiled into a normal render (u_profile = 0, a baked constant).
#ifndef VOXLAB_PROFILE_GLSL
#define VOXLAB_PROFILE_GLSL

uniform int u_profile;          // 0 normally; 1 or 2 in the profile's passes (baked)
uniform vec2 u_profile_pixel;   // the pixel profiled: (x, y), y downwards
uniform int u_profile_width;    // the target's width: fragment (x, y) is sample y * width + x
uniform int u_profile_first;    // the sample of fragment (0, 0)

int voxlab_profile_samples = -1;     // the whole ray's samples, once sample_count() has seen it
bool voxlab_profile_hit = false;     // clip_to_volume() found the ray in the region
float voxlab_profile_scalar = 0.0;   // display_value()'s last argument

// The last sample fragment i's ray keeps.
int voxlab_profile_index() {
    ivec2 f = ivec2(gl_FragCoord.xy);
    return u_profile_first + f.y * u_profile_width + f.x;
}

#endif
