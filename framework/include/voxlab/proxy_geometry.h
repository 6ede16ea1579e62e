// voxlab: proxy geometry for object-order (texture-slicing) renderers.
//
// Texture slicing draws the volume as a stack of semi-transparent polygons
// and lets the GPU's blending do the compositing. The polygons are the
// "proxy geometry": for 3D texture slicing, each is a plane perpendicular to
// the view direction cut to the volume's box; for 2D slicing, a rectangle
// across the box. The functions below are student stages written in C++:
// their reference solutions live in reference/texslice3d/ and
// reference/texslice2d/ (compiled into the framework from the stage root,
// see CMakeLists.txt), and their declarations here are the contract.
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

// 2D texture slicing keeps one stack of slices per axis and draws the stack
// most nearly facing the viewer: the axis (0 x, 1 y, 2 z) along which the
// view direction has its largest component in absolute value, so the stack
// switches where the direction is at 45 degrees between two axes. Ties go
// to the lower axis.
int chooseSliceAxis(glm::dvec3 viewDirection);

}  // namespace voxlab
