// Test corpus: the plane-box polygon written independently of the reference:
// clip the plane's crossings edge by edge from an explicit edge table, then
// order by walking: repeatedly take the point with the smallest turn.
#include "voxlab/error.h"
#include "voxlab/proxy_geometry.h"

#include <algorithm>
#include <cmath>

namespace voxlab {

namespace {

struct Edge {
    int from, to;
};

const Edge kEdges[12] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                         {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

glm::dvec3 boxCorner(const glm::dvec3& lo, const glm::dvec3& hi, int index) {
    glm::dvec3 c = lo;
    if (index & 1) c.x = hi.x;
    if (index & 2) c.y = hi.y;
    if (index & 4) c.z = hi.z;
    return c;
}

bool alreadyHave(const std::vector<glm::dvec3>& pts, const glm::dvec3& q, double tolerance) {
    return std::any_of(pts.begin(), pts.end(), [&](const glm::dvec3& r) { return glm::distance(q, r) <= tolerance; });
}

}  // namespace

std::vector<glm::dvec3> planeBoxPolygon(glm::dvec3 normal, double offset, glm::dvec3 lo, glm::dvec3 hi) {
    double m = std::max(std::abs(normal.x), std::max(std::abs(normal.y), std::abs(normal.z)));
    if (m == 0.0 || std::isnan(m) || std::isinf(m)) return std::vector<glm::dvec3>();
    glm::dvec3 unit = normal / m;
    double d = offset / m / glm::length(unit);
    unit = glm::normalize(unit);
    double size = glm::distance(lo, hi);
    std::vector<glm::dvec3> pts;
    for (const Edge& edge : kEdges) {
        glm::dvec3 p0 = boxCorner(lo, hi, edge.from);
        glm::dvec3 p1 = boxCorner(lo, hi, edge.to);
        double d0 = glm::dot(unit, p0) - d;
        double d1 = glm::dot(unit, p1) - d;
        double eps = 1e-12 * (size > 1.0 ? size : 1.0);
        glm::dvec3 hit;
        bool found = true;
        if (std::fabs(d0) <= eps) hit = p0;
        else if (std::fabs(d1) <= eps) hit = p1;
        else if (d0 * d1 < 0.0) hit = glm::mix(p0, p1, d0 / (d0 - d1));
        else found = false;
        if (found && !alreadyHave(pts, hit, 1e-9 * (size > 0.0 ? size : 1e-300))) pts.push_back(hit);
        if (std::fabs(d1) <= eps && !alreadyHave(pts, p1, 1e-9 * (size > 0.0 ? size : 1e-300))) pts.push_back(p1);
    }
    if (pts.size() < 3) return std::vector<glm::dvec3>();
    glm::dvec3 centre(0.0);
    for (size_t k = 0; k < pts.size(); ++k) centre += pts[k] / double(pts.size());
    std::vector<glm::dvec3> ordered{pts[0]};
    std::vector<bool> used(pts.size(), false);
    used[0] = true;
    while (ordered.size() < pts.size()) {
        glm::dvec3 from = ordered.back() - centre;
        int best = -1;
        double bestAngle = 10.0;
        for (size_t k = 0; k < pts.size(); ++k) {
            if (used[k]) continue;
            glm::dvec3 to = pts[k] - centre;
            double angle = std::atan2(glm::dot(glm::cross(to, from), unit), glm::dot(from, to));
            if (angle < 0.0) angle += 2.0 * 3.14159265358979;
            if (angle < bestAngle) bestAngle = angle, best = int(k);
        }
        used[size_t(best)] = true;
        ordered.push_back(pts[size_t(best)]);
    }
    return ordered;
}

}  // namespace voxlab
