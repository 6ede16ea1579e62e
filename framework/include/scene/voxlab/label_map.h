// voxlab: label maps on the CPU (tagged volume rendering; see LabelMap in
// scene.h for how a scene names one and how its labels are shown).
//
// A label map is a volume of whole numbers on the dataset's grid: the same
// dimensions, voxel for voxel (its file's own spacing is not used; the
// dataset's is). Labels are categories: 0 means "no label", and any whole
// number up to kMaxLabel names a structure. Any voxel type holds them, as
// long as every value is a whole number in 0..kMaxLabel (a float32 file
// written by a segmentation tool is fine; 2.5 or -1 is not).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/scene.h"
#include "voxlab/volume.h"

namespace voxlab {

// The labels of `labels`, one per voxel in the volume's order, after
// checking that they fit `volume`'s grid and are whole numbers in
// 0..kMaxLabel. Throws voxlab::Error with one line naming the label file:
//   "organs.nrrd: the label map is 64x64x32 but the volume is 64x64x64"
//   "organs.nrrd: a label map holds whole numbers 0..65535, not -1 (voxel 3 7 0)"
std::vector<std::uint16_t> checkedLabels(const Volume& labels, const Volume& volume);

// Which labels occur, and how often (index = label, up to the largest).
std::vector<std::uint64_t> labelCounts(const std::vector<std::uint16_t>& labels);

// The Euclidean distance, in world units, from each voxel centre to the
// nearest centre of a voxel labelled `target` (0 on those voxels), on a
// grid of `dims` voxels with `spacing`. Exact: the separable squared
// distance transform of Felzenszwalb and Huttenlocher (2012), one pass per
// axis, each weighted by that axis's spacing. Throws voxlab::Error when no
// voxel carries `target`.
std::vector<float> distanceToLabel(const std::vector<std::uint16_t>& labels, glm::ivec3 dims, glm::dvec3 spacing,
                                   int target);

// How the shaders look labels up (shaders/voxlab/labels.glsl). Row 0 of the
// transfer-function table is the scene's own function (for label 0 and every
// label without a class); each class has a row of its own. Per label L
// (index L of `rows`, for L = 0 .. largestLabel): x = its row, or -1 when
// it is hidden; y = 1 when the distance-based transfer function applies to
// it.
struct LabelRows {
    std::vector<glm::vec2> rows;
    std::vector<const TransferFunction*> tables;  // row -> its function (row 0: the scene's)
};
LabelRows labelRows(const LabelMap& map, const TransferFunction& sceneFunction, int largestLabel);

}  // namespace voxlab
