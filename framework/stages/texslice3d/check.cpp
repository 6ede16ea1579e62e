// voxlab stage texslice3d: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"
#include "voxlab/stage_library.h"

namespace voxlab::check {
namespace {

// plane_box_random (stage texslice3d)

// A grid point: v rounded to a multiple of `step` (see runPlaneBox).
glm::dvec3 onGrid(glm::dvec3 v, double step) { return glm::round(v / step) * step; }

// The plane (normal, offset: dot(n, p) = offset) of case `kind` of the
// plane-box check, for the box [lo, hi]; case `i` 5 gets a zero normal.
void randomPlane(CheckRandom& rng, int kind, int i, glm::dvec3 lo, glm::dvec3 hi, glm::dvec3& normal,
                 double& offset) {
    const double diagonal = glm::length(hi - lo);
    auto boxCorner = [&](int bits) {  // bit k set: the high side on axis k
        return glm::dvec3(bits & 1 ? hi.x : lo.x, bits & 2 ? hi.y : lo.y, bits & 4 ? hi.z : lo.z);
    };
    auto randomNormal = [&]() {
        for (;;) {
            const glm::dvec3 n = onGrid(rng.unitVector(), 1.0 / 256.0);
            if (n != glm::dvec3(0.0)) return n;
        }
    };
    // Whether every corner keeps a distance from the plane (random
    // planes must not pass "almost" through a corner).
    auto clearOfCorners = [&](glm::dvec3 n, double d) {
        for (int c = 0; c < 8; ++c)
            if (std::abs(glm::dot(n, boxCorner(c)) - d) < 1e-4 * diagonal * glm::length(n)) return false;
        return true;
    };
    for (;;) {
        normal = randomNormal();
        if (kind == 0) {  // through a random point of the box
            offset = glm::dot(normal, onGrid(rng.inBox(lo, hi), 1.0 / 1024.0));
        } else if (kind == 1) {  // parallel to a face: inside, or containing the face
            const int axis = rng.index(3), where = rng.index(3);
            normal = glm::dvec3(0.0);
            normal[axis] = rng.index(2) ? 1.0 : -1.0;
            const double at = where == 0 ? lo[axis] : where == 1 ? hi[axis]
                                                                  : onGrid(rng.inBox(lo, hi), 1.0 / 64.0)[axis];
            offset = normal[axis] * at;
            return;
        } else if (kind == 2) {  // through a corner: cutting the box there, or only touching it
            offset = glm::dot(normal, boxCorner(rng.index(8)));
            return;
        } else if (kind == 3) {  // containing an edge: through the box, or only touching it
            const int axis = rng.index(3);
            normal[axis] = 0.0;
            if (normal == glm::dvec3(0.0)) continue;
            offset = glm::dot(normal, boxCorner(rng.index(8)));
            return;
        } else if (kind == 4) {  // anywhere near the box, possibly missing it
            offset = glm::dot(normal, onGrid(rng.inBox(lo - 0.5 * (hi - lo), hi + 0.5 * (hi - lo)), 1.0 / 1024.0));
        } else {  // through the centre; once a zero normal
            if (i == 5) normal = glm::dvec3(0.0);
            offset = glm::dot(normal, 0.5 * (lo + hi));
            return;
        }
        if (clearOfCorners(normal, offset)) return;
    }
}

json runPlaneBox(const std::string&) {
    CheckRandom rng(0x5EED0007u);
    json check = checkJson("plane_box_random", "texslice3d", rng.seed());
    // Boxes on a grid of 1/64, normals on a grid of 1/256 and points on a
    // grid of 1/1024, scaled by powers of two: then every offset dot(n, p)
    // is exact in double, and a plane put through a corner or an edge
    // really passes through it.
    for (int i = 0; i < kCases; ++i) {
        // One box in ten far from the origin (2^20 away: the handout's
        // "absolute epsilons" pitfall); still exact on the grids.
        const glm::dvec3 far = i % 10 == 9 ? glm::dvec3(std::ldexp(rng.index(2) ? 1.0 : -1.0, 20)) : glm::dvec3(0.0);
        const glm::dvec3 lo = far + onGrid(rng.inBox(glm::dvec3(-2.0), glm::dvec3(2.0)), 1.0 / 64.0);
        const glm::dvec3 hi = lo + onGrid(rng.inBox(glm::dvec3(0.25), glm::dvec3(3.0)), 1.0 / 64.0);
        glm::dvec3 normal;
        double offset = 0.0;
        randomPlane(rng, i % 6, i, lo, hi, normal, offset);
        // The normal need not have unit length: scaled by 2^-10..2^10, and
        // one case in ten each by about 1e200 and 1e-300 (the handout's
        // extreme normals: |n| overflows or underflows when squared).
        const int exponent = i % 10 == 7 ? 664 : i % 10 == 8 ? -997 : rng.index(21) - 10;
        const double scale = std::ldexp(1.0, exponent);
        normal *= scale;
        offset *= scale;
        const json output = callStage([&] {
            json vertices = json::array();
            for (const glm::dvec3& v : cppStages().planeBoxPolygon(normal, offset, lo, hi))
                vertices.push_back({number(v.x), number(v.y), number(v.z)});
            return vertices;
        });
        addCase(check, "planeBoxPolygon",
                {{"normal", vecJson(normal)}, {"offset", offset}, {"lo", vecJson(lo)}, {"hi", vecJson(hi)}}, output);
    }
    return check;
}

// The largest distance between matched vertices when actual[(start + step * i) mod n]
// is matched with expected[i].
double cycleDistance(const std::vector<glm::dvec3>& expected, const std::vector<glm::dvec3>& actual, int start,
                     int step) {
    const int n = int(expected.size());
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
        const int matched = ((start + step * i) % n + n) % n;
        worst = std::max(worst, glm::length(actual[std::size_t(matched)] - expected[std::size_t(i)]));
    }
    return worst;
}

// Polygons are cycles: the same vertices (within 1e-6 times the box's
// diagonal: the reference computes them to about 1e-15 of it, so this
// only forgives another order of floating-point operations) in the same
// cyclic order, from any starting vertex. The direction is part of the
// contract (counter-clockwise seen along the normal, proxy_geometry.h), so
// a reversed polygon fails, and so does an unsorted one.
CaseVerdict comparePolygons(const json& input, const json& expected, const json& actual) {
    const double tolerance = 1e-6 * glm::length(vecOf(input.at("hi")) - vecOf(input.at("lo")));
    std::vector<glm::dvec3> e, a;
    readPoints(expected, &e);
    if (!readPoints(actual, &a)) return failure("not a list of finite vertices");
    if (a.size() != e.size())
        return failure(std::to_string(a.size()) + " vertices instead of " + std::to_string(e.size()));
    const int n = int(e.size());
    if (n == 0) return {};
    double best = std::numeric_limits<double>::infinity(), reversed = best;
    for (int start = 0; start < n; ++start) {
        best = std::min(best, cycleDistance(e, a, start, 1));
        reversed = std::min(reversed, cycleDistance(e, a, start, -1));
    }
    if (best <= tolerance) return {true, best, ""};
    if (reversed <= tolerance) return failure("the right vertices in reverse (clockwise) order");
    double farthest = 0.0;  // from an expected vertex to the nearest vertex given
    for (const glm::dvec3& p : e) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const glm::dvec3& q : a) nearest = std::min(nearest, glm::length(p - q));
        farthest = std::max(farthest, nearest);
    }
    if (farthest <= tolerance) return failure("the right vertices in the wrong order");
    return {false, farthest, "other vertices"};
}

CaseVerdict comparePlaneBox(const std::string&, const json& input, const json& e, const json& a) {
    return comparePolygons(input, e, a);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(texslice3d) {
    using namespace voxlab::check;
    checks.add("plane_box_random",
               "planeBoxPolygon() on random planes and boxes: through corners and edges, parallel to and containing "
               "faces, missing the box, normals of length ~1e200 and ~1e-300, boxes 2^20 from the origin; vertices "
               "compared as a counter-clockwise cycle",
               runPlaneBox, comparePlaneBox);
}
