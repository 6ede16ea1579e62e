// voxlab stage cutting_plane: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// half_space_random (stage cutting_plane)

json runHalfSpace(const std::string& root) {
    CheckRandom rng(0x5EED0004u);
    std::vector<glm::vec4> planePoints, planeNormals, tested, origins, directions;
    for (int i = 0; i < kCases; ++i) {
        // Kinds: 0, 1 a random plane; 2 an axis-aligned plane and a ray
        // parallel to it; 3 an axis-aligned plane and a point exactly on it.
        const int kind = i % 4;
        const int axis = rng.index(3);
        glm::dvec3 normal = unitF32(rng.unitVector());
        if (kind >= 2) {
            normal = glm::dvec3(0.0);
            normal[axis] = rng.index(2) ? 1.0 : -1.0;
        }
        const glm::dvec3 point = f32(rng.inBox(glm::dvec3(-1.0), glm::dvec3(2.0)));
        glm::dvec3 p;
        for (;;) {
            p = f32(rng.inBox(glm::dvec3(-2.0), glm::dvec3(3.0)));
            if (kind == 3) p[axis] = point[axis];
            if (kind == 3 || std::abs(glm::dot(p - point, normal)) >= 1e-3) break;
        }
        glm::dvec3 origin, direction;
        double tEntry, tExit;
        for (;;) {
            origin = f32(rng.inBox(glm::dvec3(-2.0), glm::dvec3(3.0)));
            direction = rng.unitVector();
            if (kind == 2) direction[axis] = 0.0;
            if (glm::length(direction) < 0.1) continue;
            direction = unitF32(direction);
            if (kind == 2) direction[axis] = 0.0;
            tEntry = f32(rng.range(0.0, 2.0));
            tExit = f32(tEntry + rng.range(0.05, 4.0));
            const double along = glm::dot(direction, normal), start = glm::dot(origin - point, normal);
            if (std::abs(start) < 1e-3) continue;
            if (kind == 2) break;
            if (std::abs(along) < 0.05) continue;
            const double crossing = -start / along;
            if (std::abs(crossing - tEntry) >= 1e-3 && std::abs(crossing - tExit) >= 1e-3) break;
        }
        planePoints.push_back(texel(point));
        planeNormals.push_back(texel(normal));
        tested.push_back(texel(p));
        origins.push_back(texel(origin, tEntry));
        directions.push_back(texel(direction, tExit));
    }
    GlslProbe probe(root, "stages/cutting_plane/half_space_probe.frag");
    const probe::ProbeResults results = probe.run(kCases, {planePoints, planeNormals, tested, origins, directions});
    json check = checkJson("half_space_random", "cutting_plane", rng.seed());
    auto flag = [](float v) { return std::isfinite(v) ? json(v != 0.0f) : json(nullptr); };
    for (int i = 0; i < kCases; ++i) {
        const std::size_t k = std::size_t(i);
        addCase(check, "in_half_space",
                {{"p", vecJson(glm::vec3(tested[k]))},
                 {"point", vecJson(glm::vec3(planePoints[k]))},
                 {"normal", vecJson(glm::vec3(planeNormals[k]))}},
                flag(results.first[k].x));
    }
    for (int i = 0; i < kCases; ++i) {
        const std::size_t k = std::size_t(i);
        const glm::vec4 r = results.first[k];
        addCase(check, "clip_to_half_space",
                {{"origin", vecJson(glm::vec3(origins[k]))},
                 {"direction", vecJson(glm::vec3(directions[k]))},
                 {"t_entry", double(origins[k].w)},
                 {"t_exit", double(directions[k].w)},
                 {"point", vecJson(glm::vec3(planePoints[k]))},
                 {"normal", vecJson(glm::vec3(planeNormals[k]))}},
                {{"kept", flag(r.y)}, {"t_entry", number(r.z)}, {"t_exit", number(r.w)}});
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

CaseVerdict compareHalfSpace(const std::string& function, const json&, const json& e, const json& a) {
    if (function == "in_half_space") return compareExact(e, a);
    if (!a.is_object() || !a.contains("kept")) return failure("no result");
    if (a["kept"] != e["kept"]) return failure("kept is wrong");
    if (e["kept"] != true) return {};
    // Where something is kept, the interval: crossings are at least 1e-3
    // from the ends and |dot(direction, normal)| >= 0.05, so t is well
    // conditioned: 1e-4 (1 + |t|).
    return compareNumbers(json::array({e["t_entry"], e["t_exit"]}), json::array({a["t_entry"], a["t_exit"]}), 1e-4,
                          1e-4);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(cutting_plane) {
    using namespace voxlab::check;
    checks.add("half_space_random",
               "in_half_space() and clip_to_half_space() on random planes, points and rays: points on the plane, "
               "rays parallel to it",
               runHalfSpace, compareHalfSpace);
}
