// Student starter code, generated from reference/marching_cubes/marching_cubes.cpp by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: marching cubes (Lorensen and Cline 1987), the cube's case and the
// vertex on an edge. The contract is in
// framework/stages/marching_cubes/include/voxlab/marching_cubes.h; the framework walks the cubes, looks each case up in
// its table (marchingCubesTable) and draws or saves the mesh.
//
// The cubes sit between voxel centres: the 8 corners of a cube are 8
// neighbouring voxel centres, corner c at offset (c & 1, (c >> 1) & 1,
// (c >> 2) & 1). The surface separates the corners at or above the
// isovalue ("inside") from those below; a cube's case, one bit per corner,
// says which are which, and picks its triangles from the table. Each
// triangle vertex lies on an edge whose two corners are on different
// sides, where the linear interpolation of their values crosses the
// isovalue.
#include "voxlab/marching_cubes.h"

#include "voxlab/error.h"  // NotImplemented, for the starter code

namespace voxlab {

int cubeCase(const double values[8], double isovalue) {
    // TODO: implement this function (see the comment above it).
    (void)values, (void)isovalue;  // delete this line once you use them
    throw NotImplemented("cubeCase");
}

glm::dvec3 edgeCrossing(glm::dvec3 a, glm::dvec3 b, double va, double vb, double isovalue) {
    // TODO: implement this function (see the comment above it).
    (void)a, (void)b, (void)va, (void)vb, (void)isovalue;  // delete this line once you use them
    throw NotImplemented("edgeCrossing");
}

}  // namespace voxlab
