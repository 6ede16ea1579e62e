// Test corpus: a disguised copy of reference/texslice3d/proxy_geometry.cpp (names
// changed, comments rewritten, the two lambdas and independent statements
// reordered, braces and layout changed).
#include "voxlab/error.h"
#include "voxlab/proxy_geometry.h"

#include <algorithm>
#include <cmath>

namespace voxlab {

std::vector<glm::dvec3> planeBoxPolygon(glm::dvec3 normal, double offset, glm::dvec3 lo, glm::dvec3 hi)
{
    const double big = std::max({std::abs(normal.x), std::abs(normal.y), std::abs(normal.z)});
    if (!(big > 0.0) || !std::isfinite(big))
        return {};
    const double len = glm::length(normal / big);
    const double dist = (offset / big) / len;
    const glm::dvec3 nn = (normal / big) / len;
    const double diag = glm::length(hi - lo);
    const double tol = 1e-12 * std::max(diag, 1.0);

    std::vector<glm::dvec3> out;
    auto push = [&](glm::dvec3 x) {
        for (const glm::dvec3& y : out)
        {
            if (glm::length(x - y) <= 1e-9 * std::max(diag, 1e-300)) return;
        }
        out.push_back(x);
    };
    auto vertex = [&](int k) {
        return glm::dvec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
    };
    for (int k = 0; k < 8; ++k)
    {
        for (int ax = 0; ax < 3; ++ax)
        {
            if (k & (1 << ax)) continue;
            const glm::dvec3 e0 = vertex(k), e1 = vertex(k | (1 << ax));
            const double s0 = glm::dot(nn, e0) - dist, s1 = glm::dot(nn, e1) - dist;
            if (std::abs(s0) <= tol) push(e0);
            if (std::abs(s1) <= tol) push(e1);
            if ((s0 < -tol && s1 > tol) || (s0 > tol && s1 < -tol))
                push(e0 + (s0 / (s0 - s1)) * (e1 - e0));
        }
    }
    if (out.size() < 3) return {};

    // sort by angle around the middle
    glm::dvec3 mid(0.0);
    for (const glm::dvec3& x : out) mid += x;
    mid /= double(out.size());
    const glm::dvec3 aux = std::abs(nn.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 e = glm::normalize(glm::cross(aux, nn));
    const glm::dvec3 f = glm::cross(e, nn);
    std::sort(out.begin(), out.end(), [&](const glm::dvec3& x, const glm::dvec3& y) {
        const glm::dvec3 dx = x - mid, dy = y - mid;
        return std::atan2(glm::dot(dx, f), glm::dot(dx, e)) < std::atan2(glm::dot(dy, f), glm::dot(dy, e));
    });
    return out;
}

}  // namespace voxlab
