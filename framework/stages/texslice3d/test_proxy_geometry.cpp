// Proxy geometry for 3D texture slicing, checked on the CPU (no GL):
//  planeBoxPolygon against an oracle written here by a different method:
//    Sutherland-Hodgman clipping of a large square lying in the plane by the
//    box's six half-spaces (the reference instead intersects the box's 12
//    edges and sorts the crossings by angle). Thousands of random planes and
//    boxes, plus the degenerate cuts the contract names (faces, edges,
//    corners, misses, zero normals).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "voxlab/proxy_geometry.h"

namespace voxlab::testing {
namespace {

using glm::dvec3;

constexpr double kPi = 3.14159265358979323846;

// Distances on the plane and on the box surface, and duplicates, are judged
// at 1e-9 times the box's diagonal: the contract's own threshold for
// distinct vertices. The computed points carry rounding errors of a few ulp
// of the coordinates (at most ~150 here, against a diagonal of at least
// ~0.17), i.e. below 1e-12 of the diagonal, far inside this.
constexpr double kPointTolerance = 1e-9;
// Areas agree to 1e-9 relative (a shoelace sum of a few products is good to
// ~1e-15, but a small polygon's area is small against the vertex errors),
// plus the conditioning term below. On the random planes the worst area and
// vertex differences use about 1% of these tolerances.
constexpr double kAreaRelative = 1e-9;
constexpr double kUlp = 2.220446049250313e-16;  // double epsilon

struct Box {
    dvec3 lo, hi;
    double diagonal() const { return glm::length(hi - lo); }
    dvec3 corner(int bits) const {
        return {bits & 1 ? hi.x : lo.x, bits & 2 ? hi.y : lo.y, bits & 4 ? hi.z : lo.z};
    }
};

// How far rounding can move a vertex along the box's surface. Evaluating
// the plane at a point of coordinates up to C errs by a few ulp of C; a
// vertex found where the plane crosses an edge along axis a moves by that
// error over |n_a| (unit n), and a boundary line on a face perpendicular to
// a by that error over sqrt(1 - n_a^2), the sine of the plane's angle with
// the face. A plane at grazing incidence (normals 1e-7 off an axis) thus has
// vertices that no double-precision method pins down to 1e-9 of the
// diagonal; the positional and area tolerances grow by this amount, which
// stays below 1e-12 of the diagonal for planes far from grazing.
struct Conditioning {
    double rounding;  // a few ulp of the coordinates: the error of evaluating the plane
    double sine;      // the smallest sine between the plane and an edge or face it can cross
    double shift() const { return rounding / sine; }
};

Conditioning conditioning(dvec3 n, double d, const Box& box) {
    const double length = glm::length(n);
    const dvec3 m = n / length;
    double c = std::abs(d / length);
    for (int a = 0; a < 3; ++a) c = std::max({c, std::abs(box.lo[a]), std::abs(box.hi[a])});
    c += box.diagonal();
    double sine = 1.0;
    for (int a = 0; a < 3; ++a) {
        if (m[a] != 0.0) sine = std::min(sine, std::abs(m[a]));
        const double face = std::sqrt(m[(a + 1) % 3] * m[(a + 1) % 3] + m[(a + 2) % 3] * m[(a + 2) % 3]);
        if (face != 0.0) sine = std::min(sine, face);
    }
    return {kUlp * c, sine};
}

std::string str(dvec3 p) {
    std::ostringstream s;
    s.precision(17);
    s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
    return s.str();
}

std::string describe(dvec3 n, double d, const Box& box) {
    std::ostringstream s;
    s.precision(17);
    s << "plane n=" << str(n) << " d=" << d << " box [" << str(box.lo) << ", " << str(box.hi) << "]";
    return s.str();
}

// ---------------------------------------------------------------------------
// The oracle. In an orthonormal basis (u, v) of the plane with
// cross(u, v) = -n/|n|, counter-clockwise in (u, v) coordinates is
// counter-clockwise for a viewer looking along n (the viewer's right and up
// span a frame whose third axis points back at the viewer, against n). A
// square of half side 2 diagonals around the box centre's projection covers
// the whole cut; clipping it by lo[a] <= p[a] <= hi[a] for each axis a leaves
// exactly the cut polygon, already in counter-clockwise order.

struct OraclePolygon {
    std::vector<dvec3> vertices;  // counter-clockwise seen along n
    double area = 0.0;
};

OraclePolygon clipOracle(dvec3 normal, double offset, const Box& box) {
    const double length = glm::length(normal);
    if (!(length > 0.0)) return {};
    const dvec3 m = normal / length;
    const double dist = offset / length;
    const double diag = box.diagonal();
    const dvec3 centre = 0.5 * (box.lo + box.hi);
    const dvec3 origin = centre + (dist - glm::dot(m, centre)) * m;
    const dvec3 u = glm::normalize(std::abs(m.z) < 0.9 ? glm::cross(m, dvec3(0, 0, 1)) : glm::cross(m, dvec3(1, 0, 0)));
    const dvec3 v = glm::cross(u, m);  // cross(u, cross(u, m)) = -m

    const double r = 2.0 * diag;
    std::vector<glm::dvec2> poly = {{-r, -r}, {r, -r}, {r, r}, {-r, r}};
    // A point counts as inside a half-space up to 8 ulp of the coordinates
    // beyond its face: a plane containing a face has its points computed a
    // few ulp off that face, and they must not be clipped away. (This shifts
    // the oracle's vertices by at most 8 times the conditioning above.)
    const double inside = 8.0 * conditioning(normal, offset, box).rounding;
    auto at = [&](glm::dvec2 q) { return origin + q.x * u + q.y * v; };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            // g(q) <= 0 inside: lo - p[axis] for the low face, p[axis] - hi for the high one.
            auto g = [&](glm::dvec2 q) {
                const double p = at(q)[axis];
                return side == 0 ? box.lo[axis] - p : p - box.hi[axis];
            };
            std::vector<glm::dvec2> out;
            for (std::size_t i = 0; i < poly.size(); ++i) {
                const glm::dvec2 p = poly[i], q = poly[(i + 1) % poly.size()];
                const double gp = g(p), gq = g(q);
                const bool pin = gp <= inside, qin = gq <= inside;
                if (pin != qin) out.push_back(p + (gp / (gp - gq)) * (q - p));
                if (qin) out.push_back(q);
            }
            poly = out;
            if (poly.empty()) return {};
        }

    // Merge points closer than the contract's distinct-vertex threshold,
    // then drop vertices where the boundary goes straight on (a polygon
    // squeezed into a segment or a point loses all of them).
    const double merge = kPointTolerance * diag;
    bool changed = true;
    while (changed && poly.size() >= 3) {
        changed = false;
        for (std::size_t i = 0; i < poly.size() && poly.size() >= 3; ++i) {
            const glm::dvec2 a = poly[(i + poly.size() - 1) % poly.size()], b = poly[i],
                             c = poly[(i + 1) % poly.size()];
            const double turn = (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
            if (glm::length(b - a) <= merge || turn <= 1e-12 * glm::length(b - a) * glm::length(c - b)) {
                poly.erase(poly.begin() + std::ptrdiff_t(i));
                changed = true;
                break;
            }
        }
    }
    if (poly.size() < 3) return {};
    OraclePolygon result;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 a = poly[i] - poly[0], b = poly[(i + 1) % poly.size()] - poly[0];
        result.area += 0.5 * (a.x * b.y - a.y * b.x);  // shoelace
        result.vertices.push_back(at(poly[i]));
    }
    return result;
}

// ---------------------------------------------------------------------------
// Every property of the contract, and agreement with the oracle.
::testing::AssertionResult checkPolygon(dvec3 n, double d, const Box& box, const std::vector<dvec3>& poly,
                                        const OraclePolygon& oracle) {
    const double diag = box.diagonal(), tol = kPointTolerance * diag;
    // Vertices match the oracle's within 1e-9 diagonals or, for planes near
    // grazing incidence, 16 times the rounding shift (both methods err by a
    // few times it; the oracle's inclusive clipping adds up to 8 times it).
    const double shift = 16.0 * conditioning(n, d, box).shift();
    const double match = std::max(tol, shift);
    auto fail = [&]() {
        ::testing::AssertionResult r = ::testing::AssertionFailure();
        r << describe(n, d, box) << " -> " << poly.size() << " vertices (oracle " << oracle.vertices.size()
          << "): ";
        return r;
    };
    if (poly.size() != oracle.vertices.size()) {
        auto r = fail();
        for (const dvec3& p : poly) r << str(p) << " ";
        return r;
    }
    if (poly.empty()) return ::testing::AssertionSuccess();
    const double nl = glm::length(n);
    const dvec3 m = n / nl;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const dvec3 p = poly[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return fail() << "non-finite " << str(p);
        const double off = std::abs(glm::dot(n, p) - d) / nl;
        if (!(off <= tol)) return fail() << "vertex " << str(p) << " is " << off << " off the plane";
        double onFace = 1e300;
        for (int a = 0; a < 3; ++a) {
            if (!(p[a] >= box.lo[a] - tol && p[a] <= box.hi[a] + tol))
                return fail() << "vertex " << str(p) << " outside the box";
            onFace = std::min({onFace, std::abs(p[a] - box.lo[a]), std::abs(p[a] - box.hi[a])});
        }
        if (!(onFace <= tol)) return fail() << "vertex " << str(p) << " is inside the box, on no face";
        for (std::size_t j = 0; j < i; ++j)
            if (!(glm::length(p - poly[j]) > tol))
                return fail() << "duplicate vertices " << str(p) << " " << str(poly[j]);
    }
    // Convex and counter-clockwise for a viewer looking along n: every turn
    // has dot(cross(b - a, c - b), n) < 0, and the turns add up to one full
    // circle (a star-shaped ordering would turn twice around).
    double totalTurn = 0.0;
    const std::size_t k = poly.size();
    for (std::size_t i = 0; i < k; ++i) {
        const dvec3 a = poly[i], b = poly[(i + 1) % k], c = poly[(i + 2) % k];
        const dvec3 x = glm::cross(b - a, c - b);
        if (!(glm::dot(x, n) < 0.0))
            return fail() << "turn at " << str(b) << " is not counter-clockwise seen along n (dot " << glm::dot(x, n)
                          << ")";
        totalTurn += std::atan2(glm::length(x), glm::dot(b - a, c - b));
    }
    // 1e-9 rad: the sum of at most 6 atan2 values, each good to ~1e-15.
    if (!(std::abs(totalTurn - 2.0 * kPi) <= 1e-9)) return fail() << "turns add up to " << totalTurn << " rad";
    // Area: a positive shoelace sum for the counter-clockwise-along-n order.
    dvec3 sum(0.0);
    for (std::size_t i = 0; i < k; ++i) sum += glm::cross(poly[i] - poly[0], poly[(i + 1) % k] - poly[0]);
    const double area = -0.5 * glm::dot(sum, m);
    // Moving the vertices by up to `shift` changes the area by at most the
    // perimeter times that (zero in practice away from grazing incidence).
    double perimeter = 0.0;
    for (std::size_t i = 0; i < k; ++i) perimeter += glm::length(oracle.vertices[(i + 1) % k] - oracle.vertices[i]);
    if (!(std::abs(area - oracle.area) <= kAreaRelative * oracle.area + perimeter * shift))
        return fail() << "area " << area << ", oracle " << oracle.area;
    // The same vertices in the same cyclic order as the oracle's.
    std::size_t start = 0;
    for (std::size_t j = 1; j < k; ++j)
        if (glm::length(oracle.vertices[j] - poly[0]) < glm::length(oracle.vertices[start] - poly[0])) start = j;
    for (std::size_t i = 0; i < k; ++i)
        if (!(glm::length(oracle.vertices[(start + i) % k] - poly[i]) <= match))
            return fail() << "vertex " << i << " " << str(poly[i]) << " differs from the oracle's "
                          << str(oracle.vertices[(start + i) % k]);
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult check(dvec3 n, double d, const Box& box) {
    return checkPolygon(n, d, box, planeBoxPolygon(n, d, box.lo, box.hi), clipOracle(n, d, box));
}

// Whether `points` are among the polygon's vertices (within the point tolerance).
::testing::AssertionResult hasVertices(const std::vector<dvec3>& poly, const std::vector<dvec3>& points,
                                       const Box& box) {
    for (const dvec3& q : points) {
        bool found = false;
        for (const dvec3& p : poly) found = found || glm::length(p - q) <= kPointTolerance * box.diagonal();
        if (!found) return ::testing::AssertionFailure() << str(q) << " is not a vertex";
    }
    return ::testing::AssertionSuccess();
}

double polygonArea(const std::vector<dvec3>& poly, dvec3 n) {
    dvec3 sum(0.0);
    for (std::size_t i = 0; i < poly.size(); ++i)
        sum += glm::cross(poly[i] - poly[0], poly[(i + 1) % poly.size()] - poly[0]);
    return -0.5 * glm::dot(sum, glm::normalize(n));
}

// Boxes for the special cases: a unit cube, an offset cube, an anisotropic
// box off the origin and a thin slab.
const std::vector<Box>& specialBoxes() {
    static const std::vector<Box> boxes = {
        {{0, 0, 0}, {1, 1, 1}},
        {{1, -1, 3}, {3, 1, 5}},
        {{-3, 2, 5}, {7, 2.5, 40}},
        {{10, -20, 0.5}, {10.25, 30, 1.5}},
    };
    return boxes;
}

// Smallest and largest dot(n, corner): the planes between them meet the box.
std::pair<double, double> range(dvec3 n, const Box& box) {
    double lo = 1e300, hi = -1e300;
    for (int c = 0; c < 8; ++c) {
        lo = std::min(lo, glm::dot(n, box.corner(c)));
        hi = std::max(hi, glm::dot(n, box.corner(c)));
    }
    return {lo, hi};
}

// A fixed 64-bit generator with explicit uniform and normal variates, so that
// the cases are the same on every standard library.
struct Rng {
    std::uint64_t state;
    std::uint64_t next() {  // splitmix64
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
    int below(int n) { return int(next() % std::uint64_t(n)); }
    double sign() { return below(2) ? 1.0 : -1.0; }
    double normal() {  // Box-Muller
        const double a = 1.0 - uniform(), b = uniform();
        return std::sqrt(-2.0 * std::log(a)) * std::cos(2.0 * kPi * b);
    }
};

// ---------------------------------------------------------------------------
// Random planes.

TEST(ProxyGeometry, RandomPlanesMatchTheClippingOracle) {
    Rng rng{20240611};
    const int kCases = 40000;
    std::map<std::size_t, int> counts;
    int cases = 0, throughCorners = 0, failures = 0;  // stop after 5 failures: one broken stage fails them all
    for (int i = 0; i < kCases && failures < 5; ++i, ++cases) {
        Box box;
        switch (rng.below(5)) {
            case 0: box = {{0, 0, 0}, {1, 1, 1}}; break;
            case 1: box = {{-3, 2, 5}, {7, 2.5, 40}}; break;
            case 2:  // near-cubic, off the origin
                for (int a = 0; a < 3; ++a) {
                    box.lo[a] = rng.uniform(-50, 50);
                    box.hi[a] = box.lo[a] + rng.uniform(1, 2);
                }
                break;
            default:  // anisotropic and off the origin: sides 0.1 to 100, corners within 150 of the origin
                for (int a = 0; a < 3; ++a) {
                    box.lo[a] = rng.uniform(-50, 50);
                    box.hi[a] = box.lo[a] + std::pow(10.0, rng.uniform(-1, 2));
                }
        }
        dvec3 n;
        switch (rng.below(5)) {
            case 0:  // exactly along an axis
                n = dvec3(0.0);
                n[rng.below(3)] = rng.sign();
                break;
            case 1: {  // near an axis: the other components 1e-7 to 1e-2, or zero
                const int axis = rng.below(3);
                for (int a = 0; a < 3; ++a) {
                    const double small = rng.sign() * std::pow(10.0, rng.uniform(-7, -2));
                    n[a] = a == axis ? rng.sign() : rng.below(3) ? small : 0.0;
                }
                break;
            }
            case 2:  // near a face or space diagonal of the cube
                for (int a = 0; a < 3; ++a) n[a] = rng.sign() * (rng.below(4) ? 1.0 : 0.0) + 1e-3 * rng.normal();
                break;
            default:
                n = dvec3(rng.normal(), rng.normal(), rng.normal());
        }
        n = glm::normalize(n) * std::pow(10.0, rng.uniform(-3, 3));  // any length
        // Planes through corners (exactly, up to rounding in d), tried when
        // well conditioned: rounding then moves nothing by more than 1e-10
        // diagonals. Near grazing incidence, whether a corner is cut off by a
        // sliver far below 1e-9 diagonals or not at all is decided by
        // rounding, in the code under test and in the oracle alike.
        dvec3 cn = n;
        double cd = 0.0;
        const int kind = rng.below(10);
        if (kind == 0) {  // through one corner: touching it or cutting through it
            cd = glm::dot(cn, box.corner(rng.below(8)));
        } else if (kind == 1) {  // through three corners: a face, a diagonal section, a corner triangle
            int c[3] = {rng.below(8), 0, 0};
            do c[1] = rng.below(8); while (c[1] == c[0]);
            do c[2] = rng.below(8); while (c[2] == c[0] || c[2] == c[1]);
            cn = glm::cross(box.corner(c[1]) - box.corner(c[0]), box.corner(c[2]) - box.corner(c[0]));
            cd = glm::dot(cn, box.corner(c[0]));
        } else if (kind == 2) {  // through two corners (an edge or a diagonal), otherwise random
            const int c0 = rng.below(8), c1 = (c0 + 1 + rng.below(7)) % 8;
            cn = glm::cross(box.corner(c1) - box.corner(c0), dvec3(rng.normal(), rng.normal(), rng.normal()));
            cd = glm::dot(cn, box.corner(c0));
        }
        double d;
        if (kind <= 2 && 8.0 * conditioning(cn, cd, box).shift() <= 1e-10 * box.diagonal()) {
            n = cn;
            d = cd;
            ++throughCorners;
        } else {  // across the box and up to 15% of its depth beyond either side
            const auto [lo, hi] = range(n, box);
            d = lo + (hi - lo) * rng.uniform(-0.15, 1.15);
        }
        const std::vector<dvec3> poly = planeBoxPolygon(n, d, box.lo, box.hi);
        ++counts[poly.size()];
        const ::testing::AssertionResult r = checkPolygon(n, d, box, poly, clipOracle(n, d, box));
        if (!r) {
            ADD_FAILURE() << "random case " << i << ": " << r.message();
            ++failures;
        }
    }
    std::ostringstream s;
    s << cases << " random planes (" << throughCorners << " through corners); vertex counts:";
    for (auto [size, count] : counts) s << " " << size << ": " << count;
    std::cout << "[ proxy    ] " << s.str() << "\n";
    RecordProperty("vertex_counts", s.str());
    // The generator must reach every shape, misses included.
    for (std::size_t size : {0, 3, 4, 5, 6}) EXPECT_GE(counts[size], 200) << "too few " << size << "-gons";
}

// ---------------------------------------------------------------------------
// Special cases.

TEST(ProxyGeometry, AxisAlignedPlanesThroughTheInteriorGiveTheCrossSection) {
    for (const Box& box : specialBoxes())
        for (int axis = 0; axis < 3; ++axis)
            for (double f : {0.5, 0.01, 0.99, 1.0 / 3.0})
                for (double s : {1.0, -1.0, 4.0}) {
                    dvec3 n(0.0);
                    n[axis] = s;
                    const double x = box.lo[axis] + f * (box.hi[axis] - box.lo[axis]);
                    ASSERT_TRUE(check(n, s * x, box));
                    const std::vector<dvec3> poly = planeBoxPolygon(n, s * x, box.lo, box.hi);
                    const dvec3 h = box.hi - box.lo;
                    const double expected = h.x * h.y * h.z / h[axis];
                    ASSERT_EQ(poly.size(), 4u);
                    // 1e-12 relative: a product of box sides against a shoelace sum.
                    EXPECT_NEAR(polygonArea(poly, n), expected, 1e-12 * expected);
                }
}

TEST(ProxyGeometry, PlaneContainingAFaceGivesThatFace) {
    for (const Box& box : specialBoxes())
        for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side)
                for (double s : {1.0, -1.0, 0.001, 250.0}) {
                    dvec3 n(0.0);
                    n[axis] = s;
                    const double x = side ? box.hi[axis] : box.lo[axis];
                    SCOPED_TRACE(describe(n, s * x, box));
                    ASSERT_TRUE(check(n, s * x, box));
                    std::vector<dvec3> face;
                    for (int c = 0; c < 8; ++c)
                        if (((c >> axis) & 1) == side) face.push_back(box.corner(c));
                    const std::vector<dvec3> poly = planeBoxPolygon(n, s * x, box.lo, box.hi);
                    ASSERT_EQ(poly.size(), 4u);
                    EXPECT_TRUE(hasVertices(poly, face, box));
                }
}

// The 12 edges: each runs along axis c from a corner; a and b are the other axes.
struct Edge {
    int along, a, b;
    int cornerBits;  // the edge's start corner (bit `along` clear)
};

std::vector<Edge> edges() {
    std::vector<Edge> out;
    for (int along = 0; along < 3; ++along)
        for (int bits = 0; bits < 8; ++bits)
            if (!(bits & (1 << along))) out.push_back({along, (along + 1) % 3, (along + 2) % 3, bits});
    return out;
}

TEST(ProxyGeometry, PlaneContainingAnEdge) {
    for (const Box& box : specialBoxes())
        for (const Edge& e : edges()) {
            const dvec3 p0 = box.corner(e.cornerBits), p1 = box.corner(e.cornerBits | (1 << e.along));
            // Outward signs of the two faces meeting at the edge.
            const double sa = (e.cornerBits >> e.a) & 1 ? 1.0 : -1.0, sb = (e.cornerBits >> e.b) & 1 ? 1.0 : -1.0;
            for (auto [wa, wb] : {std::pair{1.0, 1.0}, std::pair{0.3, 2.0}, std::pair{5.0, 0.01}}) {
                // Leaning outwards on both faces the plane only touches the edge: nothing.
                dvec3 n(0.0);
                n[e.a] = sa * wa;
                n[e.b] = sb * wb;
                SCOPED_TRACE(describe(n, glm::dot(n, p0), box));
                EXPECT_TRUE(check(n, glm::dot(n, p0), box));
                EXPECT_TRUE(planeBoxPolygon(n, glm::dot(n, p0), box.lo, box.hi).empty());
                // Leaning in, it cuts through the box: a rectangle with the edge as one side.
                n[e.b] = -sb * wb;
                SCOPED_TRACE(describe(n, glm::dot(n, p0), box));
                EXPECT_TRUE(check(n, glm::dot(n, p0), box));
                const std::vector<dvec3> poly = planeBoxPolygon(n, glm::dot(n, p0), box.lo, box.hi);
                EXPECT_EQ(poly.size(), 4u);
                EXPECT_TRUE(hasVertices(poly, {p0, p1}, box));
            }
            // Through the opposite edge too: the diagonal section, all four vertices corners.
            const dvec3 h = box.hi - box.lo;
            dvec3 n(0.0);
            n[e.a] = sa * h[e.b];
            n[e.b] = -sb * h[e.a];
            const int opposite = e.cornerBits ^ (1 << e.a) ^ (1 << e.b);
            const dvec3 q0 = box.corner(opposite), q1 = box.corner(opposite | (1 << e.along));
            SCOPED_TRACE(describe(n, glm::dot(n, p0), box));
            EXPECT_TRUE(check(n, glm::dot(n, p0), box));
            const std::vector<dvec3> poly = planeBoxPolygon(n, glm::dot(n, p0), box.lo, box.hi);
            EXPECT_EQ(poly.size(), 4u);
            EXPECT_TRUE(hasVertices(poly, {p0, p1, q0, q1}, box));
            const double expected = std::hypot(h[e.a], h[e.b]) * h[e.along];
            EXPECT_NEAR(polygonArea(poly, n), expected, 1e-12 * expected);  // 1e-12: shoelace rounding
        }
}

TEST(ProxyGeometry, PlaneTouchingOnlyACornerGivesNothing) {
    for (const Box& box : specialBoxes())
        for (int c = 0; c < 8; ++c)
            for (dvec3 w : {dvec3(1, 1, 1), dvec3(0.2, 3, 7), dvec3(1e-3, 1, 1e3)}) {
                dvec3 n;
                for (int a = 0; a < 3; ++a) n[a] = ((c >> a) & 1 ? 1.0 : -1.0) * w[a];  // outward at the corner
                const dvec3 p = box.corner(c);
                SCOPED_TRACE(describe(n, glm::dot(n, p), box));
                EXPECT_TRUE(check(n, glm::dot(n, p), box));
                EXPECT_TRUE(planeBoxPolygon(n, glm::dot(n, p), box.lo, box.hi).empty());
                // The same plane turned inwards on one axis cuts the box, through that corner.
                n.y = -n.y;
                SCOPED_TRACE(describe(n, glm::dot(n, p), box));
                EXPECT_TRUE(check(n, glm::dot(n, p), box));
                const std::vector<dvec3> poly = planeBoxPolygon(n, glm::dot(n, p), box.lo, box.hi);
                EXPECT_GE(poly.size(), 3u);
                EXPECT_TRUE(hasVertices(poly, {p}, box));
            }
}

TEST(ProxyGeometry, PlanesThroughThreeCorners) {
    // Every plane through three of the eight corners: faces, diagonal
    // sections (rectangles) and corner triangles.
    for (const Box& box : specialBoxes()) {
        std::map<std::size_t, int> counts;
        for (int i = 0; i < 8; ++i)
            for (int j = i + 1; j < 8; ++j)
                for (int k = j + 1; k < 8; ++k) {
                    const dvec3 a = box.corner(i), b = box.corner(j), c = box.corner(k);
                    for (double s : {1.0, -1.0}) {
                        const dvec3 n = s * glm::cross(b - a, c - a);
                        SCOPED_TRACE(describe(n, glm::dot(n, a), box));
                        EXPECT_TRUE(check(n, glm::dot(n, a), box));
                        const std::vector<dvec3> poly = planeBoxPolygon(n, glm::dot(n, a), box.lo, box.hi);
                        EXPECT_TRUE(hasVertices(poly, {a, b, c}, box));
                        if (s > 0) ++counts[poly.size()];
                    }
                }
        // Of the 56 triples, 24 lie on a face (6 faces x 4), 24 on one of the
        // 6 diagonal sections (x 4) and 8 cut off a corner.
        EXPECT_EQ(counts[3], 8);
        EXPECT_EQ(counts[4], 48);
    }
    // The unit cube cut by x + y + z = 1: the equilateral triangle of side
    // sqrt(2), area sqrt(3)/2; x + y + z = 2 gives its mirror image.
    const Box cube{{0, 0, 0}, {1, 1, 1}};
    for (double d : {1.0, 2.0}) {
        const std::vector<dvec3> poly = planeBoxPolygon({1, 1, 1}, d, cube.lo, cube.hi);
        ASSERT_EQ(poly.size(), 3u);
        EXPECT_NEAR(polygonArea(poly, {1, 1, 1}), std::sqrt(3.0) / 2.0, 1e-14);  // a few ulp of shoelace rounding
    }
}

TEST(ProxyGeometry, CrossingsCloserThanTheThresholdAreMerged) {
    // The plane through the three neighbours of a corner, moved away from
    // that corner, crosses each neighbour's two other edges near it: a
    // hexagon with three short edges. A move of s (along the unit normal)
    // puts the crossing on an edge along axis a at s / |n_a| from the corner.
    // With every such distance below 2e-10 diagonals the pairs are closer
    // than the contract's 1e-9 and merge into a triangle; a move of 1e-7
    // diagonals keeps them apart. Moved towards the corner, the plane cuts a
    // triangle either way.
    for (const Box& box : specialBoxes())
        for (int c = 0; c < 8; ++c) {
            const dvec3 a = box.corner(c ^ 1), b = box.corner(c ^ 2), e = box.corner(c ^ 4);
            const dvec3 n = glm::cross(b - a, e - a);
            const double d0 = glm::dot(n, a);
            const double away = glm::dot(n, box.corner(c)) > d0 ? -1.0 : 1.0;
            const dvec3 m = glm::abs(glm::normalize(n));
            const double merged = 2e-10 * std::min({m.x, m.y, m.z}), apart = 1e-7;
            for (auto [move, expected] :
                 {std::pair{merged, 3u}, std::pair{-merged, 3u}, std::pair{apart, 6u}, std::pair{-apart, 3u}}) {
                const double d = d0 + away * move * glm::length(n) * box.diagonal();
                SCOPED_TRACE(describe(n, d, box));
                EXPECT_TRUE(check(n, d, box));
                EXPECT_EQ(planeBoxPolygon(n, d, box.lo, box.hi).size(), expected);
            }
        }
}

TEST(ProxyGeometry, PlanesThroughTheCentreOfACube) {
    const Box cube{{1, -1, 3}, {3, 1, 5}};  // side 2
    const dvec3 c(2, 0, 4);
    // Normal (1, 1, 1): the regular hexagon through six edge midpoints, side
    // s/sqrt(2) for a cube of side s, area 3 sqrt(3)/4 s^2.
    for (dvec3 n : {dvec3(1, 1, 1), dvec3(-1, 1, 1), dvec3(1, -1, -1), dvec3(-2.5, -2.5, 2.5)}) {
        SCOPED_TRACE(describe(n, glm::dot(n, c), cube));
        EXPECT_TRUE(check(n, glm::dot(n, c), cube));
        const std::vector<dvec3> poly = planeBoxPolygon(n, glm::dot(n, c), cube.lo, cube.hi);
        ASSERT_EQ(poly.size(), 6u);
        EXPECT_NEAR(polygonArea(poly, n), 3.0 * std::sqrt(3.0), 1e-13);  // shoelace rounding
        for (const dvec3& p : poly) EXPECT_NEAR(glm::length(p - c), std::sqrt(2.0), 1e-13);  // midpoint distance
    }
    // Normal (1, 1, -2) contains the main diagonal from lo to hi: a rhombus
    // through those two corners and two edge midpoints, with diagonals
    // sqrt(3) s and sqrt(2) s, area sqrt(6)/2 s^2.
    const dvec3 n(1, 1, -2);
    EXPECT_TRUE(check(n, glm::dot(n, c), cube));
    const std::vector<dvec3> poly = planeBoxPolygon(n, glm::dot(n, c), cube.lo, cube.hi);
    ASSERT_EQ(poly.size(), 4u);
    EXPECT_TRUE(hasVertices(poly, {cube.lo, cube.hi, {3, -1, 4}, {1, 1, 4}}, cube));
    EXPECT_NEAR(polygonArea(poly, n), std::sqrt(6.0) * 2.0, 1e-13);
    // An anisotropic box cut through its centre by the normal (1/hx, 1/hy,
    // 1/hz): the affine image of the hexagon, through six edge midpoints.
    const Box box{{-3, 2, 5}, {7, 2.5, 40}};
    const dvec3 h = box.hi - box.lo, m = 1.0 / h, centre = 0.5 * (box.lo + box.hi);
    EXPECT_TRUE(check(m, glm::dot(m, centre), box));
    const std::vector<dvec3> hex = planeBoxPolygon(m, glm::dot(m, centre), box.lo, box.hi);
    ASSERT_EQ(hex.size(), 6u);
    EXPECT_TRUE(hasVertices(hex,
                            {{box.hi.x, box.lo.y, centre.z}, {box.lo.x, box.hi.y, centre.z},
                             {box.hi.x, centre.y, box.lo.z}, {box.lo.x, centre.y, box.hi.z},
                             {centre.x, box.hi.y, box.lo.z}, {centre.x, box.lo.y, box.hi.z}},
                            box));
}

TEST(ProxyGeometry, PlanesMissingTheBoxGiveNothing) {
    for (const Box& box : specialBoxes())
        for (dvec3 n : {dvec3(1, 0, 0), dvec3(0, -3, 0), dvec3(1, 2, 3), dvec3(-0.3, 1e-4, 7)}) {
            const auto [lo, hi] = range(n, box);
            for (double beyond : {1e-6, 0.5, 100.0})
                for (double d : {lo - beyond * (hi - lo), hi + beyond * (hi - lo)}) {
                    SCOPED_TRACE(describe(n, d, box));
                    EXPECT_TRUE(planeBoxPolygon(n, d, box.lo, box.hi).empty());
                    EXPECT_TRUE(check(n, d, box));
                }
        }
}

TEST(ProxyGeometry, ZeroNormalGivesNothing) {
    for (const Box& box : specialBoxes())
        for (double d : {0.0, 1.0, -2.0, 4.0})
            EXPECT_TRUE(planeBoxPolygon({0, 0, 0}, d, box.lo, box.hi).empty()) << describe({0, 0, 0}, d, box);
}

TEST(ProxyGeometry, NormalLengthDoesNotMatterAndItsSignSetsTheWinding) {
    // Scaling (n, d) by k > 0 is the same plane: the same vertices in the same
    // cyclic order. k < 0 flips the viewer, and so the order.
    const Box box{{-3, 2, 5}, {7, 2.5, 40}};
    const double tol = kPointTolerance * box.diagonal();
    for (dvec3 n : {dvec3(0.3, -0.8, 0.1), dvec3(1, 1, 1), dvec3(0, 0.2, 1)}) {
        const double d = glm::dot(n, 0.5 * (box.lo + box.hi)) + 0.1;
        const std::vector<dvec3> base = planeBoxPolygon(n, d, box.lo, box.hi);
        ASSERT_GE(base.size(), 3u);
        for (double k : {1e-4, 0.5, 3.0, 1e5, -1e-4, -1.0, -1e5}) {
            SCOPED_TRACE(describe(k * n, k * d, box));
            EXPECT_TRUE(check(k * n, k * d, box));
            const std::vector<dvec3> poly = planeBoxPolygon(k * n, k * d, box.lo, box.hi);
            ASSERT_EQ(poly.size(), base.size());
            const std::size_t size = base.size();
            std::size_t start = size;
            for (std::size_t j = 0; j < size; ++j)
                if (glm::length(poly[j] - base[0]) <= tol) start = j;
            ASSERT_LT(start, size);
            for (std::size_t i = 0; i < size; ++i) {
                const std::size_t j = k > 0 ? (start + i) % size : (start + size - i) % size;
                EXPECT_LE(glm::length(poly[j] - base[i]), tol) << "vertex " << i;
            }
        }
    }
}

// Any representable normal length works: normalising with glm::length
// alone would overflow above ~1e154 (the plane x = 0.5 with n = (1e155, 0, 0)
// gave all 8 corners) and underflow below ~1e-162 (n = (1e-170, 0, 0) gave
// nothing).
TEST(ProxyGeometry, ExtremeNormalLengths) {
    const Box cube{{0, 0, 0}, {1, 1, 1}};
    for (double s : {1e155, 1e200, 1e-170, 1e-300}) {
        SCOPED_TRACE(s);
        EXPECT_EQ(planeBoxPolygon({s, 0, 0}, 0.5 * s, cube.lo, cube.hi).size(), 4u);
    }
}

}  // namespace
}  // namespace voxlab::testing
