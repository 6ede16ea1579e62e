// voxlab: the slice axis of 2D texture slicing, the stage's C++ contract.
//
// 2D texture slicing keeps one stack of axis-aligned slices per axis and
// draws them as rectangles across the volume's box, blended by the GPU. Its
// reference solution lives in reference/texslice2d/ (compiled into the
// framework from the stage root, framework/CMakeLists.txt); the declaration
// here is the contract.
#pragma once

#include <glm/glm.hpp>

namespace voxlab {

// The stack drawn is the one most nearly facing the viewer: the axis (0 x,
// 1 y, 2 z) along which the view direction has its largest component in
// absolute value, so the stack switches where the direction is at 45
// degrees between two axes. Ties go to the lower axis.
int chooseSliceAxis(glm::dvec3 viewDirection);

}  // namespace voxlab

// The stage's C++ functions for the stage table (voxlab/stage_library.h):
// X(name, return type, parameter types).
#define VOXLAB_STAGE_FUNCTIONS_texslice2d(X) X(chooseSliceAxis, int, (glm::dvec3))
