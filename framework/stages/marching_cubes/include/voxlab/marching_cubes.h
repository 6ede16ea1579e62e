// voxlab: isosurfaces as triangle meshes, by marching cubes (Lorensen and
// Cline, SIGGRAPH 1987), for the mesh renderer and `voxlab mesh`.
//
// The cubes are the cells between voxel centres: cube (i, j, k) has the 8
// centres (i + a, j + b, k + c), a, b, c in {0, 1}, as its corners, so a
// volume of n voxels on an axis has n - 1 cubes on it. Corner c of a cube is
// at offset (c & 1, (c >> 1) & 1, (c >> 2) & 1). A cube's case is the byte
// whose bit c is set when corner c's value is at or above the isovalue (the
// marching_cubes stage's cubeCase). Its 12 edges are numbered
//    0..3  along x: corners (0,1) (2,3) (4,5) (6,7)
//    4..7  along y: corners (0,2) (1,3) (4,6) (5,7)
//    8..11 along z: corners (0,4) (1,5) (2,6) (3,7)
// and the surface crosses an edge whose two corners lie on different sides
// (the stage's edgeCrossing places the vertex there).
//
// The case table (marchingCubesTable) is built here, not copied: on each
// face of the cube the crossed edges are joined by segments (a face with
// four crossings, an ambiguous face, always keeps its two "inside" corners
// apart), the segments close into loops, and each loop is cut into a fan of
// triangles facing the lower values. Two cubes sharing a face see the same
// corners there and join its edges the same way, so the mesh has no cracks:
// on a surface that closes inside the volume every edge has exactly two
// triangles (test_marching_cubes).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/volume.h"

namespace voxlab {

// --- The marching_cubes stage (C++; reference/marching_cubes/) ---------------
// The framework calls these through cppStages() (stage_library.h).

// The cube's case: bit c (1 << c) set when values[c], the value at corner
// c, is at or above the isovalue ("inside"); 0 when no corner is, 255 when
// all are. A value equal to the isovalue counts as inside.
int cubeCase(const double values[8], double isovalue);

// Where the isosurface crosses the edge from a (value va) to b (value vb),
// va and vb on different sides of the isovalue: the point at fraction
// t = (isovalue - va) / (vb - va) from a to b, where the linear
// interpolation of the two values equals the isovalue.
glm::dvec3 edgeCrossing(glm::dvec3 a, glm::dvec3 b, double va, double vb, double isovalue);

// --- The framework's side -------------------------------------------------------

// Corner offsets and the two corners of each edge, as numbered above.
glm::ivec3 cubeCorner(int corner);
std::array<int, 2> cubeEdgeCorners(int edge);

// Per case, its triangles as triples of edges, wound counter-clockwise seen
// from the side of the lower values (so their normals point down the
// gradient, out of bright structures).
using CaseTriangles = std::vector<std::array<int, 3>>;
const std::array<CaseTriangles, 256>& marchingCubesTable();

// An indexed mesh in world coordinates.
struct TriangleMesh {
    std::vector<glm::vec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

// The isosurface of `volume` at `isovalue`: each crossed edge of the grid
// gets one vertex (shared by every triangle that uses it), placed by the
// stage's edgeCrossing, always called with the edge's lower corner first
// so that the two cubes sharing an edge agree. At most `maxTriangles`
// (voxlab::Error past it, naming the count).
TriangleMesh extractIsosurface(const Volume& volume, double isovalue, std::size_t maxTriangles = 20'000'000);

// Surface area, enclosed volume (by the divergence theorem: the sum of the
// signed volumes of the tetrahedra from the origin to each triangle, positive
// when the triangles face out of the enclosed region) and how closed the
// mesh is: edges used by one triangle only (boundary) or by more than two.
struct MeshMeasures {
    double area = 0.0;
    double volume = 0.0;
    std::size_t boundaryEdges = 0, nonManifoldEdges = 0;
    bool watertight() const { return boundaryEdges == 0 && nonManifoldEdges == 0; }
};
MeshMeasures measureMesh(const TriangleMesh& mesh);

// Writes the mesh as PLY (binary little-endian, vertices as float, faces
// as lists of 3 uint32) or Wavefront OBJ (text), by the file's extension,
// through writeFileAtomically. Throws voxlab::Error for another extension.
void saveMesh(const TriangleMesh& mesh, const std::string& path);

}  // namespace voxlab

// The stage's C++ functions for the stage table (voxlab/stage_library.h):
// X(name, return type, parameter types).
#define VOXLAB_STAGE_FUNCTIONS_marching_cubes(X)  \
    X(cubeCase, int, (const double*, double)) \
    X(edgeCrossing, glm::dvec3, (glm::dvec3, glm::dvec3, double, double, double))
