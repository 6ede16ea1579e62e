// Student starter code, generated from reference/labels/labels.glsl by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
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
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return 0;
}

// How `label` shows a data value: its row's transfer function, or nothing
// (vec4(0)) when the label is hidden.
vec4 classify_label(int label, float value) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

// Colour (rgb, not premultiplied) and opacity per unit length (a) of the
// sample at p: with u_label_masks == 0 the nearest voxel's label, else the
// blend of the 8 surrounding voxels' labels described above.
vec4 classify_labelled(vec3 p) {
    // TODO: implement this function (see the comment above it).
    not_implemented();
    return vec4(0.0);
}

#endif
