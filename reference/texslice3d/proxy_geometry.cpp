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
    // BEGIN SOLUTION
    // Scale by the largest component first: squaring a huge or tiny normal
    // in glm::length would overflow or underflow.
    const double largest = std::max({std::abs(normal.x), std::abs(normal.y), std::abs(normal.z)});
    if (!(largest > 0.0) || !std::isfinite(largest)) return {};
    const double length = glm::length(normal / largest);
    const glm::dvec3 n = (normal / largest) / length;
    const double d = (offset / largest) / length;
    const double scale = glm::length(hi - lo);
    const double eps = 1e-12 * std::max(scale, 1.0);

    // The 12 edges: from each corner with bit a clear to the corner with it set.
    auto corner = [&](int bits) {
        return glm::dvec3(bits & 1 ? hi.x : lo.x, bits & 2 ? hi.y : lo.y, bits & 4 ? hi.z : lo.z);
    };
    std::vector<glm::dvec3> points;
    auto add = [&](glm::dvec3 p) {
        for (const glm::dvec3& q : points)
            if (glm::length(p - q) <= 1e-9 * std::max(scale, 1e-300)) return;
        points.push_back(p);
    };
    for (int bits = 0; bits < 8; ++bits)
        for (int axis = 0; axis < 3; ++axis) {
            if (bits & (1 << axis)) continue;
            const glm::dvec3 a = corner(bits), b = corner(bits | (1 << axis));
            const double sa = glm::dot(n, a) - d, sb = glm::dot(n, b) - d;
            if (std::abs(sa) <= eps) add(a);
            if (std::abs(sb) <= eps) add(b);
            if ((sa < -eps && sb > eps) || (sa > eps && sb < -eps)) add(a + (sa / (sa - sb)) * (b - a));
        }
    if (points.size() < 3) return {};

    // A basis of the plane with cross(u, v) = -n: angles from u towards v
    // then turn counter-clockwise for a viewer looking along n.
    glm::dvec3 centroid(0.0);
    for (const glm::dvec3& p : points) centroid += p;
    centroid /= double(points.size());
    const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(helper, n));
    const glm::dvec3 v = glm::cross(u, n);  // cross(u, cross(u, n)) = -n
    std::sort(points.begin(), points.end(), [&](const glm::dvec3& p, const glm::dvec3& q) {
        const glm::dvec3 a = p - centroid, b = q - centroid;
        return std::atan2(glm::dot(a, v), glm::dot(a, u)) < std::atan2(glm::dot(b, v), glm::dot(b, u));
    });
    return points;
    // END SOLUTION
}

}  // namespace voxlab
