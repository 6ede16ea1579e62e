// Student starter code, generated from reference/texslice2d/slice_axis.cpp by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: choosing the slice stack for 2D texture slicing (a C++ stage).
//
// 2D slicing keeps three stacks of slices, one perpendicular to each axis.
// Seen nearly edge-on, a stack's slices would let the viewer look between
// them, so each frame draws the stack whose slices face the viewer most:
// the axis along which the view direction has its largest component. At 45
// degrees between two axes both components are equal and the image jumps
// when the stack switches: the classic artefact of the method. Ties go to
// the lower axis (x before y before z).
#include "voxlab/error.h"  // NotImplemented, for the student stubs
#include "voxlab/slice_axis.h"

#include <cmath>

namespace voxlab {

int chooseSliceAxis(glm::dvec3 viewDirection) {
    // TODO: implement this function (see the comment above it).
    (void)viewDirection;  // delete this line once you use them
    throw NotImplemented("chooseSliceAxis");
}

}  // namespace voxlab
