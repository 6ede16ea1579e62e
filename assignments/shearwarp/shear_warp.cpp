// Student starter code, generated from reference/shearwarp/shear_warp.cpp by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: shear-warp, the factorisation (Lacroute and Levoy 1994). The
// contract and the coordinates are in framework/stages/shearwarp/include/voxlab/shear_warp.h.
//
// The view direction, measured in voxels (forward / spacing), decides
// everything: the principal axis c is its largest component, so that rays
// cross every slice perpendicular to c; moving one slice along c, a ray
// moves -v_a / v_c voxels along a and -v_b / v_c along b, which the shear
// undoes. Once sheared, all points of a ray share one intermediate position
// (u, w), and the warp is the camera's projection of the slice x_c = 0,
// written in u and w.
#include "voxlab/error.h"  // NotImplemented, for the student stubs
#include "voxlab/shear_warp.h"

#include <cmath>

namespace voxlab {

ShearWarp factorShearWarp(const Camera& camera, glm::ivec3 dims, glm::dvec3 spacing) {
    if (camera.projection != Projection::Orthographic)
        throw Error("shearwarp: orthographic views only (the perspective factorisation is not implemented)");
    // TODO: implement this function (see the comment above it).
    (void)camera, (void)dims, (void)spacing;  // delete this line once you use them
    throw NotImplemented("factorShearWarp");
}

}  // namespace voxlab
