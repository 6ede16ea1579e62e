// voxlab: gradients of the volume, computed on the CPU.
//
// Shading needs a surface normal and the 2D transfer function needs the
// gradient magnitude |grad f|. The GPU can estimate both on the fly (the
// "gradient" stage, reference/gradient/gradient.glsl) or read them from a
// gradient volume precomputed here and uploaded as an RGB32F texture.
//
// Units: data units per unit length, where the unit is the volume's smallest
// voxel spacing (the same unit as opacity; see the README). On a volume with
// spacing 1, a value that grows by 3 per voxel has gradient magnitude 3.
//
// Estimators, at voxel (i,j,k), for the x component (y and z alike):
//   Central   (6 neighbours): (f[i+1] - f[i-1]) / (2 sx), times min spacing.
//   Sobel     (26 neighbours): the same difference taken on the 3x3 rows of
//             neighbours around the x axis and averaged with the weights
//             [1 2 1] x [1 2 1] in y and z (total 16): smoother, and still
//             exact on a linear function.
// Boundary handling: at a face of the grid the missing neighbour is replaced
// by the voxel itself and the difference is divided by the distance actually
// covered (sx instead of 2 sx): a one-sided difference. Neighbours used only
// for smoothing (Sobel's y and z rows) are clamped to the grid. Both
// estimators are therefore exact on a linear field everywhere, faces
// included.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/volume.h"

namespace voxlab {

enum class GradientEstimator { Central, Sobel };
const char* gradientEstimatorName(GradientEstimator e);

// One gradient per voxel, in the volume's voxel order (x fastest). The work
// takes 16 bytes a voxel; more than the volume cap (volume.h) is refused
// with a voxlab::Error before anything is allocated.
std::vector<glm::vec3> computeGradients(const Volume& volume, GradientEstimator estimator);

// The 2D histogram the 2D transfer-function editor draws: voxel counts over
// value (x axis, the data range [lo, hi]) and gradient magnitude (y axis,
// [0, gradientMax], gradientMax = the largest magnitude in the volume, by
// the same definition as above). Bin (x, y) is counts[y * valueBins + x].
struct Histogram2D {
    double valueLo = 0.0, valueHi = 0.0;
    double gradientMax = 0.0;
    int valueBins = 0, gradientBins = 0;
    std::vector<std::uint64_t> counts;
};

Histogram2D histogram2D(const Volume& volume, int valueBins = 256, int gradientBins = 128,
                        GradientEstimator estimator = GradientEstimator::Central);

}  // namespace voxlab
