// voxlab: cubic B-spline coefficients of a volume, so that the cubic
// B-spline interpolates it (the "bspline" interpolation, the cubic stage).
//
// The cubic B-spline weights the coefficients of the 4 nearest centres on
// each axis; at a voxel centre only three weights are non-zero: 1/6, 4/6,
// 1/6. So the spline passes through the voxel values s exactly when, on
// every line of voxels,
//     (c[k-1] + 4 c[k] + c[k+1]) / 6 = s[k]   for k = 0 .. n-1,
// with the coefficients extended past the ends as the shader reads them,
// clamped: c[-1] = c[0], c[n] = c[n-1]. That is a tridiagonal system,
// diagonally dominant, solved exactly along x, then y, then z (the 3D
// condition is the product of the three 1D ones). Unser's recursive filter
// (pole sqrt(3) - 2; M. Unser, "Splines: a perfect fit for signal and image
// processing", IEEE Signal Processing Magazine 16(6), 1999) solves the same
// system with mirrored ends; here the ends match the shader's clamping, so
// the border voxels are interpolated too.
#pragma once

#include <vector>

#include "voxlab/volume.h"

namespace voxlab {

// One coefficient per voxel, in the volume's order, as float (the GPU's
// texture); computed in double.
std::vector<float> bsplineCoefficients(const Volume& volume);

// The same for one line of n values (in place), exposed for tests.
void bsplineCoefficientsLine(std::vector<double>& line);

}  // namespace voxlab
