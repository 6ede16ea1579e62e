// voxlab: marching cubes (see marching_cubes.h): the case table, built from
// the cube's faces, and the extraction, measuring and export of meshes.
//
// Why the table is built and not typed in: the 256 cases follow from two
// rules, and a table built from rules can be read, and tested, as rules.
//  1. On a face, the crossed edges pair up into segments. Two crossings: one
//     segment. Four (the face's inside corners sit on a diagonal): each
//     inside corner is cut off by its own segment, joining the two edges
//     that meet at it. The rule looks at the face alone, so the cube on the
//     other side of the face draws the same segments: no cracks.
//  2. Each crossed edge lies on two faces, so it ends two segments: the
//     segments close into loops around the cube. Each loop becomes a fan of
//     triangles, turned to face the loop's outside corners (the lower
//     values).
#include "voxlab/marching_cubes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <unordered_map>

#include "voxlab/atomic_file.h"
#include "voxlab/error.h"
#include "voxlab/stage_library.h"

namespace voxlab {
namespace {

constexpr int kEdgeCorners[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                     {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

int edgeBetween(int a, int b) {
    for (int e = 0; e < 12; ++e)
        if ((kEdgeCorners[e][0] == a && kEdgeCorners[e][1] == b) || (kEdgeCorners[e][0] == b && kEdgeCorners[e][1] == a))
            return e;
    throw Error("marching cubes: corners " + std::to_string(a) + " and " + std::to_string(b) + " share no edge");
}

// The 4 corners of each face in cyclic order.
std::array<std::array<int, 4>, 6> faces() {
    std::array<std::array<int, 4>, 6> out{};
    int f = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3), base = side << axis;
            out[std::size_t(f++)] = {base, base | u, base | u | v, base | v};
        }
    return out;
}

// Rule 1: the segments (pairs of edges) on every face for one case.
std::vector<std::array<int, 2>> faceSegments(int cubeCase) {
    const auto inside = [&](int corner) { return (cubeCase >> corner & 1) != 0; };
    std::vector<std::array<int, 2>> segments;
    for (const std::array<int, 4>& face : faces()) {
        std::vector<int> crossed;  // face edge k joins corners k and k + 1
        for (int k = 0; k < 4; ++k)
            if (inside(face[std::size_t(k)]) != inside(face[std::size_t((k + 1) % 4)])) crossed.push_back(k);
        const auto edge = [&](int k) { return edgeBetween(face[std::size_t(k % 4)], face[std::size_t((k + 1) % 4)]); };
        if (crossed.size() == 2) {
            segments.push_back({edge(crossed[0]), edge(crossed[1])});
        } else if (crossed.size() == 4) {
            for (int k = 0; k < 4; ++k)  // cut off each inside corner: its two face edges
                if (inside(face[std::size_t(k)])) segments.push_back({edge(k + 3), edge(k)});
        }
    }
    return segments;
}

glm::dvec3 edgeMidpoint(int e) {
    return 0.5 * glm::dvec3(cubeCorner(kEdgeCorners[e][0]) + cubeCorner(kEdgeCorners[e][1]));
}

// Rule 2: loops of edges, each fanned into triangles facing its outside corners.
CaseTriangles caseTriangles(int cubeCase) {
    const std::vector<std::array<int, 2>> segments = faceSegments(cubeCase);
    std::map<int, std::vector<int>> next;
    for (const auto& s : segments) next[s[0]].push_back(s[1]), next[s[1]].push_back(s[0]);
    CaseTriangles triangles;
    std::vector<bool> used(12, false);
    for (const auto& [start, neighbours] : next) {
        if (used[std::size_t(start)]) continue;
        std::vector<int> loop = {start};
        used[std::size_t(start)] = true;
        for (int previous = -1, at = start;;) {
            const std::vector<int>& n = next[at];
            const int to = n[0] != previous ? n[0] : n[1];
            if (to == start) break;
            loop.push_back(to), used[std::size_t(to)] = true;
            previous = at, at = to;
        }
        // Which way the loop faces: its polygon's normal against the step
        // from its edges' inside corners to their outside corners.
        glm::dvec3 normal(0.0), outward(0.0);
        for (std::size_t i = 0; i < loop.size(); ++i) {
            normal += glm::cross(edgeMidpoint(loop[i]), edgeMidpoint(loop[(i + 1) % loop.size()]));
            const int a = kEdgeCorners[loop[i]][0], b = kEdgeCorners[loop[i]][1];
            const int in = (cubeCase >> a & 1) ? a : b, out = in == a ? b : a;
            outward += glm::dvec3(cubeCorner(out) - cubeCorner(in));
        }
        if (glm::dot(normal, outward) < 0.0) std::reverse(loop.begin(), loop.end());
        for (std::size_t i = 1; i + 1 < loop.size(); ++i) triangles.push_back({loop[0], loop[i], loop[i + 1]});
    }
    return triangles;
}

std::uint64_t edgeKey(glm::ivec3 lower, int axis, glm::ivec3 dims) {
    return ((std::uint64_t(lower.z) * std::uint64_t(dims.y) + std::uint64_t(lower.y)) * std::uint64_t(dims.x) +
            std::uint64_t(lower.x)) * 3 + std::uint64_t(axis);
}

}  // namespace

glm::ivec3 cubeCorner(int corner) { return {corner & 1, (corner >> 1) & 1, (corner >> 2) & 1}; }

std::array<int, 2> cubeEdgeCorners(int edge) { return {kEdgeCorners[edge][0], kEdgeCorners[edge][1]}; }

const std::array<CaseTriangles, 256>& marchingCubesTable() {
    static const std::array<CaseTriangles, 256> table = [] {
        std::array<CaseTriangles, 256> t;
        for (int c = 0; c < 256; ++c) t[std::size_t(c)] = caseTriangles(c);
        return t;
    }();
    return table;
}

// The stage is called a slab of cubes at a time (one k), first every
// cube's case, then the crossing of every edge the slab's triangles meet
// first (stage_library.h's batches: one round trip each when the stage runs
// in a stage host). The mesh is the one a cube-by-cube loop makes: vertices
// are numbered in the order their edges are first used.
TriangleMesh extractIsosurface(const Volume& volume, double isovalue, std::size_t maxTriangles) {
    volume.requireInMemory("marching cubes");
    const auto& table = marchingCubesTable();
    const CppStageBatches& batch = stageBatches();
    const glm::ivec3 d = volume.dims();
    const glm::dvec3 spacing = volume.spacing();
    TriangleMesh mesh;
    std::unordered_map<std::uint64_t, std::uint32_t> vertexOfEdge;
    const auto centre = [&](glm::ivec3 ijk) { return (glm::dvec3(ijk) + 0.5) * spacing; };
    const std::size_t cubes = std::size_t(std::max(d.x - 1, 0)) * std::size_t(std::max(d.y - 1, 0));
    std::vector<double> values(cubes * 8);
    std::vector<decltype(batch.cubeCase)::Call> caseCalls(cubes);
    for (std::size_t cube = 0; cube < cubes; ++cube) caseCalls[cube] = {&values[8 * cube], isovalue};
    std::vector<int> cases(cubes);
    std::vector<decltype(batch.edgeCrossing)::Call> crossings;
    std::vector<glm::dvec3> points;
    for (int k = 0; k + 1 < d.z; ++k) {
        double* v = values.data();
        for (int j = 0; j + 1 < d.y; ++j)
            for (int i = 0; i + 1 < d.x; ++i)
                for (int c = 0; c < 8; ++c, ++v) {
                    const glm::ivec3 p = glm::ivec3(i, j, k) + cubeCorner(c);
                    *v = volume.value(p.x, p.y, p.z);
                }
        batch.cubeCase.run(caseCalls.data(), cubes, cases.data());
        const std::uint32_t firstNew = std::uint32_t(mesh.vertices.size());
        crossings.clear();
        std::size_t cube = 0;
        for (int j = 0; j + 1 < d.y; ++j)
            for (int i = 0; i + 1 < d.x; ++i, ++cube) {
                const int cubeCase = cases[cube];
                if (cubeCase < 0 || cubeCase > 255)
                    throw Error("cubeCase returned " + std::to_string(cubeCase) + ", not a case 0..255");
                const double* corner = &values[8 * cube];
                for (const std::array<int, 3>& tri : table[std::size_t(cubeCase)]) {
                    std::array<std::uint32_t, 3> out{};
                    for (int n = 0; n < 3; ++n) {
                        const int e = tri[std::size_t(n)];
                        const int ca = kEdgeCorners[e][0], cb = kEdgeCorners[e][1];
                        const glm::ivec3 a = glm::ivec3(i, j, k) + cubeCorner(ca);
                        const glm::ivec3 b = glm::ivec3(i, j, k) + cubeCorner(cb);
                        const auto [it, fresh] = vertexOfEdge.try_emplace(
                            edgeKey(a, e / 4, d), firstNew + std::uint32_t(crossings.size()));
                        if (fresh)  // the edge's lower corner (a) first, always
                            crossings.emplace_back(centre(a), centre(b), corner[ca], corner[cb], isovalue);
                        out[std::size_t(n)] = it->second;
                    }
                    mesh.triangles.push_back(out);
                    if (mesh.triangles.size() > maxTriangles)
                        throw Error(volume.name() + ": the isosurface has more than " + std::to_string(maxTriangles) +
                                    " triangles");
                }
            }
        points.resize(crossings.size());
        batch.edgeCrossing.run(crossings.data(), crossings.size(), points.data());
        for (const glm::dvec3& p : points) mesh.vertices.push_back(glm::vec3(p));
    }
    return mesh;
}

MeshMeasures measureMesh(const TriangleMesh& mesh) {
    MeshMeasures m;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (const auto& t : mesh.triangles) {
        const glm::dvec3 a(mesh.vertices[t[0]]), b(mesh.vertices[t[1]]), c(mesh.vertices[t[2]]);
        m.area += 0.5 * glm::length(glm::cross(b - a, c - a));
        m.volume += glm::dot(a, glm::cross(b, c)) / 6.0;
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t p = t[std::size_t(e)], q = t[std::size_t((e + 1) % 3)];
            ++uses[{std::min(p, q), std::max(p, q)}];
        }
    }
    for (const auto& [edge, count] : uses) {
        m.boundaryEdges += count == 1;
        m.nonManifoldEdges += count > 2;
    }
    return m;
}

namespace {

std::string plyText(const TriangleMesh& mesh) {
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment voxlab marching cubes\nelement vertex " +
                      std::to_string(mesh.vertices.size()) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(mesh.triangles.size()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
    const std::size_t header = out.size();
    out.resize(header + mesh.vertices.size() * 12 + mesh.triangles.size() * 13);
    char* p = &out[header];
    for (const glm::vec3& v : mesh.vertices) std::memcpy(p, &v.x, 12), p += 12;  // x86-64 and ARM: little-endian
    for (const auto& t : mesh.triangles) {
        *p++ = 3;
        std::memcpy(p, t.data(), 12), p += 12;
    }
    return out;
}

std::string objText(const TriangleMesh& mesh) {
    std::string out = "# voxlab marching cubes: " + std::to_string(mesh.vertices.size()) + " vertices, " +
                      std::to_string(mesh.triangles.size()) + " triangles\n";
    char line[96];
    for (const glm::vec3& v : mesh.vertices) {
        std::snprintf(line, sizeof line, "v %.7g %.7g %.7g\n", v.x, v.y, v.z);
        out += line;
    }
    for (const auto& t : mesh.triangles) {  // OBJ counts from 1
        std::snprintf(line, sizeof line, "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1);
        out += line;
    }
    return out;
}

}  // namespace

void saveMesh(const TriangleMesh& mesh, const std::string& path) {
    std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".ply") return writeFileAtomically(path, plyText(mesh));
    if (ext == ".obj") return writeFileAtomically(path, objText(mesh));
    throw Error(path + ": unknown mesh format (expected .ply or .obj)");
}

}  // namespace voxlab
