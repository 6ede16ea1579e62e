// Stage: label maps (tagged volume rendering).
//
// Besides the data, the scene has a label map: a volume on the same grid
// whose voxels hold whole numbers naming structures (1 = enamel, 2 = dentine,
// ...; 0 = no label). Each label has its own 1D transfer function, or is
// hidden, so a structure can be shown in its own colours even where its
// values overlap another's (Tiede et al. 1998; Hadwiger et al. 2003).
//
// A label is a category, not a quantity: interpolating labels 1 and 3 gives
// 2, a structure that is not there. So a sample between voxels finds its
// label without interpolating it:
//  - nearest (labels.sampling "nearest"): the label of the voxel that
//    contains the sample, as sample_nearest() finds that voxel;
//  - masks ("masks"): each of the 8 voxels around the sample (the ones
//    trilinear interpolation reads) classifies the sample's value with its
//    own label's function, and the 8 classifications are blended with the
//    trilinear weights, premultiplied as in pre-classification. This is the
//    same as interpolating each label's indicator mask: borders between
//    labels come out smooth instead of in voxel-sized steps.
// Either way the value being classified is the interpolated data value
// sample_volume(p): only the label is looked up, never blended.
//
// The framework gives you (voxlab/labels.glsl): label_voxel(ivec3) reads one
// voxel's label, label_row(label) says which row of the label table
// classifies it (-1 when the label is hidden), and
// label_transfer_function(row, value) is that row's function at a value:
// colour (rgb) and opacity per unit length (a).
#ifndef VOXLAB_STAGE_LABELS_GLSL
#define VOXLAB_STAGE_LABELS_GLSL

#include "voxlab/volume.glsl"
#include "voxlab/labels.glsl"

// The label of the voxel whose cell contains p.
int label_at(vec3 p) {
    // BEGIN SOLUTION
    return label_voxel(ivec3(floor(voxel_coordinates(p))));
    // END SOLUTION
}

// How `label` shows a data value: its row's transfer function, or nothing
// (vec4(0)) when the label is hidden.
vec4 classify_label(int label, float value) {
    // BEGIN SOLUTION
    int row = label_row(label);
    if (row < 0) return vec4(0.0);
    return label_transfer_function(row, value);
    // END SOLUTION
}

// Colour (rgb, not premultiplied) and opacity per unit length (a) of the
// sample at p: with u_label_masks == 0 the nearest voxel's label, else the
// blend of the 8 surrounding voxels' labels described above.
vec4 classify_labelled(vec3 p) {
    // BEGIN SOLUTION
    float value = sample_volume(p);
    if (u_label_masks == 0) return classify_label(label_at(p), value);
    vec3 u = voxel_coordinates(p) - 0.5;
    vec3 lower = floor(u);
    vec3 w = u - lower;
    vec4 sum = vec4(0.0);
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 o = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        vec3 weights = mix(1.0 - w, w, vec3(o));
        vec4 c = classify_label(label_voxel(ivec3(lower) + o), value);
        sum += weights.x * weights.y * weights.z * vec4(c.rgb * c.a, c.a);
    }
    return sum.a > 0.0 ? vec4(sum.rgb / sum.a, sum.a) : vec4(0.0);
    // END SOLUTION
}

#endif
