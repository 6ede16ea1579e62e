// Student starter code, generated from reference/texslice3d/proxy_geometry.cpp by tools/make_assignments.py.
// Implement the functions marked TODO; everything else is given.
// Stage: proxy geometry for 3D texture slicing (a C++ stage).
//
// The plane dot(n, p) = d meets the box [lo, hi] in a convex polygon. Find
// its corners where the plane crosses the box's 12 edges: along an edge from
// a to b, s(t) = dot(n, a + t (b - a)) - d is linear in t, so the edge is
// crossed at t = s(a) / (s(a) - s(b)) when s(a) and s(b) have different
// signs (or one of them is zero: the plane passes through that corner).
// Then:
//  - drop points that coincide (a plane through a corner crosses three
//    edges there; a plane containing an edge or a face meets it everywhere,
//    but only its endpoints are corners of the polygon);
//  - fewer than 3 distinct points is a corner or an edge touched: nothing;
//  - order the points by angle around their centroid, measured in a basis
//    (u, v) of the plane chosen so that increasing angle runs
//    counter-clockwise for a viewer looking along n (see proxy_geometry.h).
#include "voxlab/error.h"  // NotImplemented, for the student stubs
#include "voxlab/proxy_geometry.h"

#include <algorithm>
#include <cmath>

namespace voxlab {

std::vector<glm::dvec3> planeBoxPolygon(glm::dvec3 normal, double offset, glm::dvec3 lo, glm::dvec3 hi) {
    // TODO: implement this function (see the comment above it).
    (void)normal, (void)offset, (void)lo, (void)hi;  // delete this line once you use them
    throw NotImplemented("planeBoxPolygon");
}

}  // namespace voxlab
