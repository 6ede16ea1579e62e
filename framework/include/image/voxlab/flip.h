// voxlab: the FLIP image-difference metric (LDR-FLIP) and its heat map.
//
// P. Andersson, J. Nilsson, T. Akenine-Möller, M. Oskarsson, K. Åström,
// M. D. Fairchild, "FLIP: A Difference Evaluator for Alternating Images",
// Proc. ACM Comput. Graph. Interact. Tech. 3(2), 2020 (HPG 2020).
//
// FLIP estimates, per pixel, how visible the difference between a reference
// and a test image is to someone flipping between them on a display. It has
// two parts, both computed per pixel:
//
//  - the colour error ΔEc in [0, 1]: both images are filtered with the
//    contrast sensitivity functions of the achromatic and the two chromatic
//    opponent channels (so detail too fine to see at the viewing distance
//    is removed), then compared with the HyAB distance in a Hunt-adjusted
//    L*a*b* space, compressed and remapped so that the largest possible
//    difference (pure green against pure blue) gives 1;
//  - the feature error ΔEf in [0, 1]: the difference of edge and point
//    strength (Gaussian first and second derivatives of the luminance,
//    about the width of the eye's edge detectors).
//
// The error is ΔE = ΔEc^(1 - ΔEf): feature differences raise colour errors.
// 0 means no visible difference, 1 the largest.
//
// The viewing condition enters as pixels per degree of visual angle; the
// default 67 is the paper's: a 0.7 m wide 3840-pixel monitor seen from
// 0.7 m, so one degree spans 0.7 m · π / 180 on the screen, i.e.
// 3840 / 0.7 · 0.7 · π / 180 ≈ 67.0 pixels.
//
// Both images are compared as displayed: sRGB-encoded colours, each
// channel clamped to [0, 1] (a PNG's values / 255, as loadPng gives them).
// Alpha is ignored. Pixels within a few pixels of the border see filters
// that repeat the border pixels (clamp to edge).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "voxlab/image.h"

namespace voxlab {

struct FlipResult {
    int width = 0, height = 0;
    // Per-pixel error ΔE in [0, 1], row by row, row 0 at the top (as in Image).
    std::vector<float> map;
    // Its two factors, same layout: the colour error ΔEc and the feature
    // error ΔEf, with map = colorError^(1 - featureError).
    std::vector<float> colorError, featureError;
    double mean = 0.0;  // the mean of map: FLIP's usual one-number summary
    double max = 0.0;

    // The p-th percentile of map, p in [0, 100] (0: its minimum, 50: the
    // median, 100: its maximum), interpolating linearly between the sorted
    // values as numpy's default does. Throws voxlab::Error for p outside
    // [0, 100] or an empty map.
    double percentile(double p) const;
};

// LDR-FLIP of test against reference. Throws voxlab::Error when the images
// differ in size or are empty, or pixelsPerDegree is not a positive number.
FlipResult flip(const Image& reference, const Image& test, double pixelsPerDegree = 67.0);

// The magma colour map at t in [0, 1] (clamped): black through purple and
// orange to pale yellow. Perceptually uniform, as FLIP's error maps use.
glm::vec3 magma(double t);

// The error map as an opaque RGB image, each pixel magma(error).
Image heatmap(const FlipResult& result);

}  // namespace voxlab
