// voxlab GLSL library: label maps (tagged volume rendering).
//
// A label map is a second volume on the dataset's grid whose voxels hold
// whole numbers, categories that are never interpolated (0 means "no
// label"). Each label is shown with its own 1D transfer function, or
// hidden. What the framework gives the labels stage (labels/labels.glsl):
//   label_voxel(ijk)    the label stored at voxel ijk (clamped to the grid);
//   label_row(label)    which row of the label table classifies it, -1 when
//                       the label is hidden;
//   label_transfer_function(row, value)   that row's transfer function at a
//                       data value: colour (rgb) and opacity per unit length
//                       (a), as transfer_function(value) gives for the scene's.
// Row 0 is the scene's own transfer function: label 0 and every label
// without a class of its own use it.
//
// The distance-based transfer function (Tappenbeck et al. 2006) is the
// framework's worked option: u_label_distance holds, per voxel, the distance
// in world units to the nearest voxel of one label (computed on the CPU), and
// a second function over distance recolours the labels it applies to.
#ifndef VOXLAB_LABELS_GLSL
#define VOXLAB_LABELS_GLSL

#include "voxlab/volume.glsl"

uniform usampler3D u_labels;
uniform sampler2D u_label_rows;  // per label value: (row or -1, distance applies)
uniform int u_label_count;       // label values in u_label_rows: 0 .. count-1
uniform sampler2D u_label_tf;    // one row per class, u_label_tf_size entries over u_label_tf_range
uniform int u_label_tf_size;
uniform vec2 u_label_tf_range;
uniform int u_label_masks;       // 0: labels.sampling "nearest", 1: "masks"
uniform int u_label_distance_on;
uniform sampler3D u_label_distance;
uniform sampler2D u_distance_tf;
uniform int u_distance_tf_size;
uniform vec2 u_distance_tf_range;

int label_voxel(ivec3 ijk) {
    ijk = clamp(ijk, ivec3(0), u_volume_dims - 1);
    return int(texelFetch(u_labels, ijk, 0).r);
}

vec2 label_entry(int label) {
    if (label >= u_label_count) return vec2(0.0);  // not in the data: row 0, no distance
    return texelFetch(u_label_rows, ivec2(label % 4096, label / 4096), 0).rg;
}

int label_row(int label) {
    return int(label_entry(label).x);
}

// Entries interpolated in float, as transfer_function() does (classify.glsl).
vec4 label_transfer_function(int row, float value) {
    float f = clamp((value - u_label_tf_range.x) / max(u_label_tf_range.y - u_label_tf_range.x, 1e-30), 0.0, 1.0);
    float x = f * float(u_label_tf_size - 1);
    int i = min(int(x), max(u_label_tf_size - 2, 0));
    vec4 lo = texelFetch(u_label_tf, ivec2(i, row), 0);
    vec4 hi = texelFetch(u_label_tf, ivec2(min(i + 1, u_label_tf_size - 1), row), 0);
    return mix(lo, hi, x - float(i));
}

// The distance-based function at a distance (world units).
vec4 distance_transfer_function(float d) {
    float f = clamp((d - u_distance_tf_range.x) / (u_distance_tf_range.y - u_distance_tf_range.x), 0.0, 1.0);
    float x = f * float(u_distance_tf_size - 1);
    int i = min(int(x), max(u_distance_tf_size - 2, 0));
    int j = min(i + 1, u_distance_tf_size - 1);
    vec4 lo = texelFetch(u_distance_tf, ivec2(i % 4096, i / 4096), 0);
    vec4 hi = texelFetch(u_distance_tf, ivec2(j % 4096, j / 4096), 0);
    return mix(lo, hi, x - float(i));
}

// A sample of colour c with label `label` at p, recoloured by its distance
// to the chosen label when the distance function applies to that label:
// colour from the distance function, opacity multiplied by its opacity.
vec4 apply_label_distance(vec4 c, int label, vec3 p) {
    if (label_entry(label).y == 0.0) return c;
    vec4 d = distance_transfer_function(filtered(u_label_distance, p / u_volume_extent).r);
    return vec4(d.rgb, c.a * d.a);
}

#endif
