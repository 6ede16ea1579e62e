// voxlab: proxy geometry for 3D texture slicing, the stage's C++ contract.
//
// Texture slicing draws the volume as a stack of semi-transparent polygons
// and lets the GPU's blending do the compositing. The polygons are the
// "proxy geometry": for 3D texture slicing, each is a plane perpendicular to
// the view direction cut to the volume's box. planeBoxPolygon is a student
// stage written in C++: its reference solution lives in reference/texslice3d/
// (compiled into the framework from the stage root, framework/CMakeLists.txt),
// and its declaration here is the contract.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace voxlab {

// The polygon where the plane dot(normal, p) = offset meets the box
// [lo, hi]: the plane cuts a convex box in a convex polygon of 3 to 6
// vertices, or in nothing. `normal` need not be unit length; a zero normal
// gives nothing.
//
// Returned vertices lie on the plane and on the box's surface, with no two
// closer than 1e-9 times the box's diagonal, ordered counter-clockwise as
// seen by a viewer looking along `normal` (so that for consecutive vertices
// a, b, c, dot(cross(b - a, c - b), normal) < 0). Degenerate cuts (the plane
// touching a corner or an edge, fewer than 3 distinct points) give an empty
// polygon; a plane containing a face gives that face.
std::vector<glm::dvec3> planeBoxPolygon(glm::dvec3 normal, double offset, glm::dvec3 lo, glm::dvec3 hi);

}  // namespace voxlab

// The stage's C++ functions for the stage table (voxlab/stage_library.h):
// X(name, return type, parameter types).
#define VOXLAB_STAGE_FUNCTIONS_texslice3d(X) \
    X(planeBoxPolygon, std::vector<glm::dvec3>, (glm::dvec3, double, glm::dvec3, glm::dvec3))
