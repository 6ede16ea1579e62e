// voxlab stage marching_cubes: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"
#include "voxlab/stage_library.h"

namespace voxlab::check {
namespace {

// marching_cubes_random (stage marching_cubes, C++): cubeCase on random
// corner values (some exactly at the isovalue, all above, all below) and
// edgeCrossing on random edges crossed either way.

json runMarchingCubes(const std::string&) {
    CheckRandom rng(0x5EED0014u);
    json check = checkJson("marching_cubes_random", "marching_cubes", rng.seed());
    for (int i = 0; i < kCases; ++i) {
        const double iso = f32(rng.range(-100.0, 100.0));
        double values[8];
        for (double& v : values) v = f32(iso + rng.range(-50.0, 50.0));
        if (i % 4 == 1)  // corners exactly at the isovalue count as inside
            for (double& v : values)
                if (rng.index(3) == 0) v = iso;
        if (i % 16 == 2)
            for (double& v : values) v = iso + 1.0;  // every corner inside: 255
        if (i % 16 == 3)
            for (double& v : values) v = iso - 1.0;  // none: 0
        json corners = json::array();
        for (double v : values) corners.push_back(v);
        addCase(check, "cubeCase", {{"values", corners}, {"isovalue", iso}},
                callStage([&] { return json(cppStages().cubeCase(values, iso)); }));
    }
    for (int i = 0; i < kCases; ++i) {
        const glm::dvec3 a = f32(rng.inBox(glm::dvec3(-50.0), glm::dvec3(50.0)));
        const glm::dvec3 b = f32(a + rng.unitVector() * rng.range(0.3, 4.0));
        const double iso = f32(rng.range(-10.0, 10.0));
        double below = f32(iso - rng.range(0.01, 30.0)), above = f32(iso + rng.range(0.01, 30.0));
        if (i % 8 == 5) above = iso;  // the upper corner exactly at the isovalue: the vertex is there
        if (rng.index(2)) std::swap(below, above);  // crossed either way
        addCase(check, "edgeCrossing",
                {{"a", vecJson(a)}, {"b", vecJson(b)}, {"va", below}, {"vb", above}, {"isovalue", iso}},
                callStage([&] { return vecJson(cppStages().edgeCrossing(a, b, below, above, iso)); }));
    }
    check["not_implemented"] = false;
    return check;
}

CaseVerdict compareMarchingCubes(const std::string& function, const json&, const json& e, const json& a) {
    if (function == "cubeCase") return compareExact(e, a);  // a case number
    // A point from one division and one multiply-add in double, coordinates
    // up to 55: 1e-9 (1 + |x|).
    return compareNumbers(e, a, 1e-9, 1e-9);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(marching_cubes) {
    using namespace voxlab::check;
    checks.add("marching_cubes_random",
               "cubeCase() on random corner values (some exactly at the isovalue, all above, all below) and "
               "edgeCrossing() on random edges crossed either way, one corner exactly at the isovalue on some",
               runMarchingCubes, compareMarchingCubes);
}
