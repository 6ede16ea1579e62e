// Test corpus: the plane-box polygon written independently: intersect the
// plane with the lines x = const, y = const on each pair of axes, and sort by a
// pseudo-angle in a 2D projection.
#include "voxlab/error.h"
#include "voxlab/proxy_geometry.h"

#include <algorithm>
#include <cmath>

namespace voxlab {

std::vector<glm::dvec3> planeBoxPolygon(glm::dvec3 normal, double offset, glm::dvec3 lo, glm::dvec3 hi) {
    std::vector<glm::dvec3> result;
    double biggest = 0.0;
    for (int a = 0; a < 3; a++) biggest = std::max(biggest, std::abs(normal[a]));
    if (!std::isfinite(biggest) || biggest <= 0.0) return result;
    glm::dvec3 n = normal / biggest;
    double off = offset / biggest;
    double len = std::sqrt(glm::dot(n, n));
    n /= len;
    off /= len;
    double extent = glm::length(hi - lo);
    double tiny = extent * 1e-9;
    if (tiny <= 0.0) tiny = 1e-300;
    // For each axis a, the four edges parallel to it: fix the other two axes at lo or hi.
    for (int a = 0; a < 3; a++) {
        int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int corner = 0; corner < 4; corner++) {
            glm::dvec3 start;
            start[a] = lo[a];
            start[b] = (corner & 1) ? hi[b] : lo[b];
            start[c] = (corner & 2) ? hi[c] : lo[c];
            glm::dvec3 stop = start;
            stop[a] = hi[a];
            double fa = glm::dot(n, start) - off, fb = glm::dot(n, stop) - off;
            std::vector<glm::dvec3> found;
            double zero = 1e-12 * std::max(1.0, extent);
            if (std::abs(fa) <= zero) found.push_back(start);
            if (std::abs(fb) <= zero) found.push_back(stop);
            if ((fa > zero && fb < -zero) || (fa < -zero && fb > zero)) {
                double t = fa / (fa - fb);
                glm::dvec3 q = start;
                q[a] = start[a] + t * (stop[a] - start[a]);
                found.push_back(q);
            }
            for (const glm::dvec3& q : found) {
                bool duplicate = false;
                for (const glm::dvec3& r : result) duplicate = duplicate || glm::length(q - r) <= tiny;
                if (!duplicate) result.push_back(q);
            }
        }
    }
    if (result.size() < 3) return {};
    glm::dvec3 middle = glm::dvec3(0.0);
    for (const glm::dvec3& q : result) middle += q;
    middle *= 1.0 / result.size();
    glm::dvec3 axisU = glm::normalize(std::abs(n.z) < 0.9 ? glm::cross(n, glm::dvec3(0, 0, 1)) : glm::cross(n, glm::dvec3(1, 0, 0)));
    glm::dvec3 axisV = glm::cross(n, axisU);
    auto key = [&](const glm::dvec3& q) {
        double x = glm::dot(q - middle, axisU), y = glm::dot(q - middle, axisV);
        double pseudo = y / (std::abs(x) + std::abs(y));
        return x >= 0.0 ? pseudo : 2.0 - pseudo;
    };
    std::sort(result.begin(), result.end(), [&](const glm::dvec3& p, const glm::dvec3& q) { return key(p) < key(q); });
    return result;
}

}  // namespace voxlab
