// Student starter code, generated from reference/splat/splat_order.cpp by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: splatting, the walk. The contract is in
// framework/stages/splat/include/voxlab/splatting.h: three nested loops over the voxels, back to front.
//
// Splats are laid "over" what is already drawn, so a voxel must be drawn
// before any voxel in front of it. On a regular grid seen along d, walking
// each axis from its far end towards the viewer does that: along an axis
// where d points to larger indices, the far voxels are the large ones. The
// outer loop goes along the axis closest to the view direction, so that
// whole slices facing the viewer are drawn one after the other.
#include "voxlab/error.h"  // NotImplemented, for the student stubs
#include "voxlab/splatting.h"

#include <algorithm>

namespace voxlab {

SplatOrder splatOrder(glm::dvec3 viewDirection) {
    // TODO: implement this function (see the comment above it).
    (void)viewDirection;  // delete this line once you use them
    throw NotImplemented("splatOrder");
}

}  // namespace voxlab
