// Student starter code, generated from reference/preintegration/preintegration.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: pre-integrated classification.
//
// Post-classification looks the transfer function up once per sample. A
// ray that steps over a thin feature of the transfer function (a narrow
// opacity peak, a sharp edge) misses it or catches it by chance from one
// pixel to the next: slices and rings appear, and only a smaller step
// (more samples) helps. Pre-integration (Engel, Kraus and Ertl 2001;
// Roettger et al. 2000) treats the ray as segments instead of points: between
// two samples the value is taken to run linearly from the front value sf to
// the back value sb, and the segment's colour and opacity are the exact
// emission-absorption integral of the transfer function along that line.
// That integral depends only on (sf, sb) and the segment's length, so it is
// computed once into a 2D table and each segment is one lookup.
//
// preintegrate_segment(sf, sb, len, n): the segment of length len (in unit
// lengths, the smallest spacing) cut into n equal sub-segments, each
// classified at its middle value s_k = mix(sf, sb, (k + 1/2) / n) and
// composited front to back, as the composite stage does a ray:
//     a_k = opacity_correction(transfer_function(s_k).a, len / n)
//     C  += (1 - A) a_k c_k,   A += (1 - A) a_k
// It returns vec4(C, A): the colour premultiplied by opacity, and the
// segment's opacity. The framework fills the table with it (one texel per
// pair of values; see framework/stages/preintegration/preintegration_table.frag), with
// n at least the number of table texels and of transfer-function entries
// between sf and sb, so no feature of the function falls between two
// sub-segments.
//
// classify_preintegrated(p, ray): the segment that starts at sample p and
// ends one step (u_step, world units) further along the ray. Its values are
// sf = sample_volume(p) and sb = sample_volume(p + u_step * ray.direction).
// The table u_preintegration_table is PREINTEGRATION_TABLE_SIZE texels
// square over the transfer function's range u_tf_range on both axes (x:
// front, y: back): texel i holds the value lo + i (hi - lo) / (size - 1),
// and its centre is at texture coordinate (i + 1/2) / size. Values outside
// the range are clamped to it. Read it between texels with
// filtered(u_preintegration_table, uv) (voxlab/filtering.glsl): the GPU's
// bilinear filtering, which the grader computes the same on every OpenGL.
//
// The compositing loops of the composite stage stay as they are: they
// expect a colour (not premultiplied) and an opacity per unit length, and
// correct the opacity for the step themselves. So the segment's opacity A
// is turned back into an opacity per unit length, a = 1 - (1 - A)^(1 / u_step_units)
// (then opacity_correction(a, u_step_units) gives A again), and its colour
// is C / A (zero where A is zero).
#ifndef VOXLAB_STAGE_PREINTEGRATION_GLSL
#define VOXLAB_STAGE_PREINTEGRATION_GLSL

#include "voxlab/ray.glsl"
#include "voxlab/classify.glsl"

#define PREINTEGRATION_TABLE_SIZE 256
uniform sampler2D u_preintegration_table;

// The colour (premultiplied) and opacity of a segment of length `len` unit
// lengths along which the value runs linearly from `front` to `back`,
// integrated in `substeps` sub-segments.
vec4 preintegrate_segment(float front, float back, float len, int substeps) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

// Colour (not premultiplied) and opacity per unit length of the segment
// from sample p to the next sample of `ray`, from the table.
vec4 classify_preintegrated(vec3 p, Ray ray) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

#endif
