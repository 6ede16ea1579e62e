// Coverage as a rule: the grader grades everything a handout asks for.
//
// For every graded stage (reference/<stage>/grading.json with points):
//  R1  the functions of the handout's checklist (README.md, "- [ ]" items:
//      the first backquoted signature "type name(") are exactly the
//      manifest's "functions";
//  R2  each function is graded by at least two items (scenes or function
//      checks whose "functions" name it; none named means all), so that one
//      broken function costs more than one item;
//  R3  a stage whose solution reads data values (sample_volume, voxel_value,
//      sample_nearest/trilinear, transfer_function, texelFetch, texture( in
//      its code, comments left out) has a scene whose volume holds negative
//      values: "intensities are never below 0" is a real mistake;
//  R4  a stage whose solution depends on spacing (u_step, u_step_units,
//      u_min_spacing, u_spacing, u_slice_spacing, opacity_correction) has a
//      scene whose smallest spacing is not 1, so that world units and unit
//      lengths differ;
//  R5  a scene that claims to exercise jitter_start renders with jitter on.
// The oracle is the data itself: each scene's volume is loaded and its
// values and spacing measured; the code is read for what it uses, not what
// the manifest says about it. The second test shows that the rules bite:
// taking away one covering scene or check fails them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "voxlab/grading.h"
#include "voxlab/scene.h"
#include "voxlab/volume.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
const fs::path kReference = fs::path(VOXLAB_SOURCE_DIR) / "reference";

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The functions a handout's checklist asks for; an item that names another
// stage's folder (assignments/<other>/) belongs to that stage's handout.
std::set<std::string> checklistFunctions(const std::string& readme, const std::string& stage = "") {
    std::set<std::string> out;
    std::istringstream in(readme);
    std::string item;
    auto take = [&] {
        static const std::regex folder("assignments/(\\w+)/");
        std::smatch other;
        if (!stage.empty() && std::regex_search(item, other, folder) && other[1] != stage) item.clear();
        static const std::regex span("`([^`]*)`");
        static const std::regex signature(R"(^\s*[\w:<>,]+(?:\s+[\w:<>,]+)*?\s+(\w+)\s*\()");
        for (auto it = std::sregex_iterator(item.begin(), item.end(), span); it != std::sregex_iterator(); ++it) {
            std::smatch m;
            const std::string code = (*it)[1];
            if (std::regex_search(code, m, signature)) {
                out.insert(m[1]);
                break;
            }
        }
        item.clear();
    };
    for (std::string line; std::getline(in, line);) {
        const bool starts = line.rfind("- [ ]", 0) == 0;
        const bool continues = !item.empty() && !line.empty() && (line[0] == ' ' || line[0] == '\t') &&
                               line.find("- [ ]") == std::string::npos;
        if (starts) {
            take();
            item = line;
        } else if (continues) {
            item += " " + line;
        } else if (!item.empty()) {
            take();
        }
    }
    take();
    return out;
}

std::string withoutComments(const std::string& code) {
    static const std::regex comments(R"(//[^\n]*|/\*[\s\S]*?\*/)");
    return std::regex_replace(code, comments, " ");
}

std::string stageCode(const StageManifest& m) {
    std::string code;
    for (const std::string& f : m.files) code += withoutComments(readText(kReference / m.stage / f));
    return code;
}

struct VolumeFacts {
    double minValue = 0.0, minSpacing = 1.0;
};

const VolumeFacts& facts(const std::string& dataset) {
    static std::map<std::string, VolumeFacts> cache;
    auto found = cache.find(dataset);
    if (found == cache.end()) {
        const Volume v = loadVolume(dataset);
        const glm::dvec3 s = v.spacing();
        found = cache.emplace(dataset, VolumeFacts{v.minValue(), std::min({s.x, s.y, s.z})}).first;
    }
    return found->second;
}

bool names(const std::vector<std::string>& functions, const std::string& f) {
    return functions.empty() || std::find(functions.begin(), functions.end(), f) != functions.end();
}

// What is missing from one stage's grading; empty when it is covered.
std::vector<std::string> coverageProblems(const StageManifest& m) {
    std::vector<std::string> problems;
    const std::string where = m.stage + ": ";
    const std::set<std::string> checklist = checklistFunctions(readText(kReference / m.stage / "README.md"), m.stage);
    const std::set<std::string> declared(m.functions.begin(), m.functions.end());
    for (const std::string& f : checklist)
        if (!declared.count(f)) problems.push_back(where + "the handout asks for " + f + "(), the manifest does not grade it");
    for (const std::string& f : declared)
        if (!checklist.count(f)) problems.push_back(where + f + "() is graded but not in the handout's checklist");
    for (const std::string& f : m.functions) {
        int items = 0;
        for (const GradedScene& s : m.scenes) items += names(s.functions, f);
        for (const GradedCheck& c : m.checks) items += names(c.functions, f);
        if (items < 2) problems.push_back(where + f + "() is graded by " + std::to_string(items) + " item(s), fewer than 2");
    }
    const std::string code = stageCode(m);
    static const std::regex readsValues(
        R"(\b(sample_volume|voxel_value|sample_nearest|sample_trilinear|transfer_function|texelFetch|texture)\s*\()");
    static const std::regex usesSpacing(R"(\b(u_step|u_step_units|u_min_spacing|u_spacing|u_slice_spacing|opacity_correction)\b)");
    bool signedScene = false, anisotropicScene = false;
    for (const GradedScene& s : m.scenes) {
        const Scene scene = Scene::load(s.scenePath);
        const VolumeFacts& v = facts(scene.dataset);
        signedScene = signedScene || v.minValue < 0.0;
        anisotropicScene = anisotropicScene || v.minSpacing != 1.0;
        const auto jitter = scene.parameters.find("jitter");
        if (names(s.functions, "jitter_start") && declared.count("jitter_start") &&
            (jitter == scene.parameters.end() || jitter->second == 0.0))
            problems.push_back(where + "scene " + s.name + " claims to exercise jitter_start() without jitter");
    }
    if (std::regex_search(code, readsValues) && !signedScene)
        problems.push_back(where + "reads data values, but no scene has negative values (signed data)");
    if (std::regex_search(code, usesSpacing) && !anisotropicScene)
        problems.push_back(where + "depends on spacing, but no scene has a smallest spacing other than 1");
    return problems;
}

std::vector<StageManifest> gradedManifests() {
    std::vector<StageManifest> out;
    for (const StageManifest& m : stageManifests(kReference.string()))
        if (m.points > 0) out.push_back(m);
    return out;
}

TEST(StageCoverage, EveryHandoutPromiseIsGraded) {
    const std::vector<StageManifest> manifests = gradedManifests();
    ASSERT_GE(manifests.size(), 14u);
    for (const StageManifest& m : manifests) {
        EXPECT_FALSE(checklistFunctions(readText(kReference / m.stage / "README.md"), m.stage).empty())
            << m.stage << ": no function found in the handout's checklist";
        for (const std::string& p : coverageProblems(m)) ADD_FAILURE() << p;
    }
}

// Each stage with one item removed at a time: the removals that break a
// rule are printed (the items the coverage rests on); the ones named below
// must break it.
TEST(StageCoverage, RemovingACoveringSceneOrCheckFailsTheRule) {
    std::set<std::string> critical;
    for (const StageManifest& m : gradedManifests()) {
        for (std::size_t i = 0; i < m.scenes.size() + m.checks.size(); ++i) {
            StageManifest fewer = m;
            std::string name;
            if (i < m.scenes.size()) {
                name = m.scenes[i].name;
                fewer.scenes.erase(fewer.scenes.begin() + long(i));
            } else {
                name = m.checks[i - m.scenes.size()].name;
                fewer.checks.erase(fewer.checks.begin() + long(i - m.scenes.size()));
            }
            const std::vector<std::string> problems = coverageProblems(fewer);
            if (problems.empty()) continue;
            critical.insert(m.stage + "/" + name);
            std::printf("without %-45s %s\n", (m.stage + "/" + name).c_str(), problems.front().c_str());
        }
    }
    // The only jitter scenes, the only signed scene of a stage, a function's
    // second item.
    for (const char* item : {"composite/headsq_hu_jitter", "average/headsq_hu_oblique", "firsthit/headsq_hu_skin_depth",
                             "cutting_plane/half_space_random", "slab_mip/headsq_offset"})
        EXPECT_TRUE(critical.count(item)) << "removing " << item << " should break the coverage rules";
}

TEST(StageCoverage, TheChecklistParserFindsSignatures) {
    const std::set<std::string> got = checklistFunctions(
        "## What to implement\n"
        "- [ ] `assignments/mip/mip.glsl`: `float mip_ray(Ray ray)`. It returns\n"
        "  the largest value.\n"
        "- [ ] **C++**, `assignments/texslice2d/slice_axis.cpp`:\n"
        "  `int chooseSliceAxis(glm::dvec3 viewDirection)`. It returns 0, 1 or 2.\n"
        "- [ ] `std::vector<glm::dvec3> planeBoxPolygon(glm::dvec3 normal, double offset)`\n"
        "  - [ ] the plane is normal·p = offset; `glm::length(normal)` is not needed\n"
        "\n"
        "- Not a checklist item: `vec3 other(vec3 p)`.\n");
    EXPECT_EQ(got, (std::set<std::string>{"mip_ray", "chooseSliceAxis", "planeBoxPolygon"}));
}

}  // namespace
}  // namespace voxlab::testing
