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
    // BEGIN SOLUTION
    SplatOrder order;
    const glm::dvec3 size = glm::abs(viewDirection);
    // The axes by |d|, largest first; stable, so a tie keeps the lower axis first.
    std::stable_sort(order.axes.begin(), order.axes.end(), [&](int a, int b) { return size[a] > size[b]; });
    for (int a = 0; a < 3; ++a) order.step[std::size_t(a)] = viewDirection[a] > 0.0 ? -1 : 1;
    return order;
    // END SOLUTION
}

}  // namespace voxlab
