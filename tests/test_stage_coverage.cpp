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
//  R5  a scene that claims to exercise jitter_start renders with jitter on;
//  R6  every condition the stage's code reads, and every one its manifest
//      names ("conditions"), is shown by a graded item that has it: some
//      item with the condition fails, by more than its tolerance, when the
//      stage's code is made blind to the condition (see "Conditions" below).
// The oracle is the data itself: each scene's volume is loaded and its
// values and spacing measured; the code is read for what it uses, not what
// the manifest says about it. The removal tests show that the rules bite:
// taking away one covering scene or check fails them.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "voxlab/error.h"
#include "voxlab/function_checks.h"
#include "voxlab/gl_context.h"
#include "voxlab/grading.h"
#include "voxlab/image.h"
#include "voxlab/render_engine.h"
#include "voxlab/renderer.h"
#include "voxlab/scene.h"
#include "voxlab/shader.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume.h"
#include "support/temp_dir.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
const fs::path kReference = fs::path(VOXLAB_SOURCE_DIR) / "reference";

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

// Every volume the tests read, loaded once (grading scenes share datasets).
std::map<std::string, Volume>& volumeCache() {
    static std::map<std::string, Volume> volumes;
    return volumes;
}

const Volume& loadedVolume(const std::string& dataset) {
    auto found = volumeCache().find(dataset);
    if (found == volumeCache().end()) found = volumeCache().emplace(dataset, loadVolume(dataset)).first;
    return found->second;
}

const VolumeFacts& facts(const std::string& dataset) {
    static std::map<std::string, VolumeFacts> cache;
    auto found = cache.find(dataset);
    if (found == cache.end()) {
        const Volume& v = loadedVolume(dataset);
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

// ---------------------------------------------------------------------------
// Conditions (R6). A mistake can be wrong only under some condition of the
// data, the scene or the renderer's parameters: "thickness x step" equals
// "thickness x smallest spacing" at step 1, "skip samples equal to 0" needs
// exact zeros, setting alpha to 1 on termination is invisible on black. The
// conditions, by name:
//   signed              the data in the region of interest hold negative values
//   zeros               ... hold exact zeros
//   spacing             the smallest spacing is not 1 (world units and unit
//                       lengths differ)
//   step                a ray caster's step is not 1 unit length
//   interpolation:MODE  the scene samples with MODE (nearest, trilinear, ...)
//   jitter              jitter is on
//   early_termination   front to back with early termination below 1
//   background          the background is not black
//   clip_planes:R       renderer R draws the scene with clip planes
//   perspective, orthographic   the projection
//   parameter:P         a renderer parameter P the stage's code reads
//                       (uniform u_P) is not 0
// A stage has the conditions its code reads (conditionsByRule) and those
// its manifest names. A scene has a condition by its settings and its data
// (sceneConditions); a check by its manifest entry's "conditions".
//
// Shown is measured. A witness is the stage's code made blind to the
// condition; it must fail some item that has the condition by more than
// the item's tolerance (a rendering compared as the grader compares, or a
// check run on its random inputs). A rule's witness is generic: one
// quantity of one function's solution at a time replaced by what it is
// without the condition (blindFor, blindFunction), so it equals the
// reference wherever the condition is absent (ABlindLeaves... checks it); the stage's mutants that name the condition in
// mutants.json are witnesses too; a condition with neither is witnessed by
// the starter code's stub. Clip planes are witnessed by the scene drawn
// without them (the planes must cut something the stage's code keeps).

// The names a condition may have: the fixed ones and the prefixed ones.
bool knownCondition(const std::string& c) {
    static const std::set<std::string> fixed = {"signed",     "zeros",      "spacing",     "step",
                                                "jitter",     "background", "perspective", "orthographic",
                                                "early_termination"};
    for (const char* prefix : {"interpolation:", "clip_planes:", "parameter:"})
        if (c.rfind(prefix, 0) == 0 && c.size() > std::strlen(prefix)) return true;
    return fixed.count(c) > 0;
}

std::string shaderText(const Renderer& r) {
    const auto generated = r.generatedShaders();
    const auto found = generated.find(r.fragmentShader());
    if (found != generated.end()) return found->second;
    // The framework's own entry shader, wherever it lives (a stage's folder).
    return readText(ShaderLibrary({projectRoot() + "/shaders"}).resolve(r.fragmentShader()));
}

// The body of `function` in GLSL text (from its "{" to the matching "}").
std::string functionBody(const std::string& text, const std::string& function) {
    const std::regex header("\\b" + function + R"(\s*\([^;{]*\)\s*\{)");
    std::smatch m;
    if (!std::regex_search(text, m, header)) return "";
    std::size_t at = std::size_t(m.position(0) + m.length(0)), depth = 1;
    const std::size_t from = at;
    for (; at < text.size() && depth > 0; ++at) depth += text[at] == '{' ? 1 : text[at] == '}' ? -1 : 0;
    return text.substr(from, at - from);
}

// Whether a renderer casts rays sampled at the scene's step (its entry
// shader clips rays to the region it samples).
bool castsRays(const std::string& id) {
    static std::map<std::string, bool> cache;
    auto found = cache.find(id);
    if (found == cache.end()) {
        const std::string text = withoutComments(shaderText(rendererRegistry().get(id)));
        found = cache.emplace(id, std::regex_search(text, std::regex(R"(\bclip_to_volume\s*\()"))).first;
    }
    return found->second;
}

// Renderers whose entry shader applies the scene's clip planes (through
// ray.glsl's clip_to_volume or inside_region).
std::vector<std::string> clipPlaneRenderers() {
    std::vector<std::string> out;
    for (const auto& r : rendererRegistry().all()) {
        const std::string text = withoutComments(shaderText(*r));
        if (std::regex_search(text, std::regex(R"(\b(clip_to_volume|inside_region)\s*\()"))) out.push_back(r->id());
    }
    return out;
}

// Whether ray.glsl calls `function` for the clip planes.
bool clipPlanesCall(const std::string& function) {
    const std::string ray = withoutComments(readText(fs::path(projectRoot()) / "shaders/voxlab/ray.glsl"));
    const std::regex call("\\b" + function + R"(\s*\()");
    return std::regex_search(functionBody(ray, "clip_to_volume"), call) ||
           std::regex_search(functionBody(ray, "inside_region"), call);
}

// The renderers a stage's scenes draw with (a cutting plane's other side too).
std::set<std::string> stageRenderers(const StageManifest& m) {
    std::set<std::string> out;
    for (const GradedScene& s : m.scenes) {
        const Scene scene = Scene::load(s.scenePath);
        out.insert(scene.renderer);
        if (scene.cuttingPlane && scene.cuttingPlane->otherRenderer != "none") out.insert(scene.cuttingPlane->otherRenderer);
    }
    return out;
}

// The uniform type ("float", "int") the stage declares for u_NAME, or "".
std::string uniformType(const std::string& code, const std::string& name) {
    std::smatch m;
    if (std::regex_search(code, m, std::regex(R"(\buniform\s+(float|int|bool)\s+u_)" + name + R"(\b)"))) return m[1];
    return "";
}

// The conditions a stage's code reads.
std::set<std::string> conditionsByRule(const StageManifest& m) {
    const std::string code = stageCode(m);
    std::set<std::string> out;
    auto reads = [&](const char* pattern) { return std::regex_search(code, std::regex(pattern)); };
    if (reads(R"(\b(sample_volume|voxel_value|sample_nearest|sample_trilinear|transfer_function|texelFetch|texture)\s*\()"))
        out.insert("signed");
    if (reads(R"(\b(u_step|u_step_units|u_min_spacing|u_spacing|u_slice_spacing|u_volume_extent)\b)")) out.insert("spacing");
    bool marches = false;
    for (const std::string& r : stageRenderers(m)) marches = marches || castsRays(r);
    // The step is in sight: a step quantity, or the smallest spacing where
    // voxlab/ray.glsl declares the step too.
    if (marches && (reads(R"(\b(u_step|u_step_units|opacity_correction)\b)") ||
                    (reads(R"(\bu_min_spacing\b)") && code.find("voxlab/ray.glsl") != std::string::npos)))
        out.insert("step");
    const std::regex mode(R"(\bu_interpolation\s*==\s*(\d))");
    for (auto it = std::sregex_iterator(code.begin(), code.end(), mode); it != std::sregex_iterator(); ++it)
        out.insert(std::string("interpolation:") + interpolationName(Interpolation(std::stoi((*it)[1]))));
    if (reads(R"(\bpixel_random\s*\()")) out.insert("jitter");
    if (reads(R"(\bu_early_termination\b)")) out.insert("early_termination"), out.insert("background");
    // A ray's direction is the view's only in orthographic views, its origin
    // the camera's only in perspective.
    if (reads(R"(\bray\.direction\b|\bu_cam_forward\b)")) out.insert("perspective");
    if (reads(R"(\bray\.origin\b|\bu_cam_position\b)")) out.insert("orthographic");
    bool clips = false;
    for (const std::string& f : m.functions) clips = clips || clipPlanesCall(f);
    if (clips)
        for (const std::string& r : clipPlaneRenderers()) out.insert("clip_planes:" + r);
    std::set<std::string> parameters;
    for (const auto& r : rendererRegistry().all())
        for (const ParameterSpec& p : r->parameters()) parameters.insert(p.name);
    for (const std::string& p : parameters)
        if (p != "early_termination" && !uniformType(code, p).empty()) out.insert("parameter:" + p);
    return out;
}

// What a region of interest of a dataset holds (voxels meeting the box).
struct RegionFacts {
    bool negative = false, zero = false;
};

RegionFacts regionFacts(const Scene& scene) {
    static std::map<std::string, RegionFacts> cache;
    const Volume& v = loadedVolume(scene.dataset);
    glm::dvec3 lo(0.0), hi(v.dims());
    if (scene.roi) lo = glm::max(lo, scene.roi->min), hi = glm::min(hi, scene.roi->max);
    const glm::ivec3 a(glm::floor(lo)), b(glm::ceil(hi));
    char key[160];
    std::snprintf(key, sizeof key, " %d %d %d %d %d %d", a.x, a.y, a.z, b.x, b.y, b.z);
    auto found = cache.find(scene.dataset + key);
    if (found != cache.end()) return found->second;
    RegionFacts f;
    for (int k = a.z; k < b.z; ++k)
        for (int j = a.y; j < b.y; ++j)
            for (int i = a.x; i < b.x; ++i) {
                const double value = v.value(i, j, k);
                f.negative = f.negative || value < 0.0;
                f.zero = f.zero || value == 0.0;
            }
    return cache.emplace(scene.dataset + key, f).first->second;
}

// The renderers that draw a scene, each with its resolved parameter values.
std::vector<std::pair<std::string, ParameterValues>> sceneRenderers(const Scene& scene) {
    const glm::dvec2 range = loadedVolume(scene.dataset).valueRange();
    std::vector<std::pair<std::string, ParameterValues>> out;
    out.push_back({scene.renderer, rendererRegistry().get(scene.renderer).resolveParameters(scene.parameters, range)});
    if (scene.cuttingPlane && scene.cuttingPlane->otherRenderer != "none") {
        const std::string& other = scene.cuttingPlane->otherRenderer;
        out.push_back({other, rendererRegistry().get(other).resolveParameters(scene.cuttingPlane->otherParameters, range)});
    }
    return out;
}

// The conditions a scene has, by its settings and its data.
std::set<std::string> sceneConditions(const GradedScene& graded) {
    const Scene scene = Scene::load(graded.scenePath);
    const Volume& v = loadedVolume(scene.dataset);
    const RegionFacts region = regionFacts(scene);
    std::set<std::string> out;
    if (region.negative) out.insert("signed");
    if (region.zero) out.insert("zeros");
    if (v.minSpacing() != 1.0) out.insert("spacing");
    out.insert(std::string("interpolation:") + interpolationName(scene.interpolation));
    if (scene.background != glm::vec3(0.0f)) out.insert("background");
    out.insert(scene.camera.projection == Projection::Perspective ? "perspective" : "orthographic");
    for (const auto& [id, values] : sceneRenderers(scene)) {
        if (castsRays(id) && scene.step != 1.0) out.insert("step");
        if (values.count("jitter") && values.at("jitter") != 0.0) out.insert("jitter");
        if (values.count("early_termination") && values.at("early_termination") < 1.0 &&
            values.at("back_to_front") == 0.0)
            out.insert("early_termination");
        if (!scene.clipPlanes.empty()) out.insert("clip_planes:" + id);
        for (const auto& [name, value] : values)
            if (value != 0.0) out.insert("parameter:" + name);
    }
    return out;
}

// A witness: the stage's files as changed (file name -> text; the others
// as the reference has them), or the starter code's stub; a scene drawn
// without its clip planes.
struct Witness {
    std::string label;
    std::map<std::string, std::string> files;
    bool stub = false, withoutClipPlanes = false;
    std::string key;  // unique in its stage (a blind's label repeats across conditions)
};

bool isGlslFile(const std::string& name) {
    for (const char* ext : {".glsl", ".frag", ".vert"})
        if (name.size() > std::strlen(ext) && name.compare(name.size() - std::strlen(ext), std::string::npos, ext) == 0)
            return true;
    return false;
}

// A solution block of a GLSL file: [begin, end), the function it is in and
// where that function's definition starts.
struct SolutionBlock {
    std::string function;
    std::size_t begin = 0, end = 0, functionStart = 0;
};

std::vector<SolutionBlock> solutionBlocks(const std::string& text) {
    std::vector<SolutionBlock> out;
    static const std::regex header(R"(^(?!uniform\b|const\b|struct\b|layout\b|in\b|out\b|return\b)[A-Za-z_][\w<>]*\s+(\w+)\s*\()");
    std::string function;
    std::size_t functionStart = 0, at = 0;
    while (at < text.size()) {
        const std::size_t eol = std::min(text.find('\n', at), text.size());
        const std::string line = text.substr(at, eol - at);
        std::smatch m;
        if (std::regex_search(line, m, header) && line.find(';') == std::string::npos) function = m[1], functionStart = at;
        if (line.find("BEGIN SOLUTION") != std::string::npos) out.push_back({function, eol, eol, functionStart});
        if (line.find("END SOLUTION") != std::string::npos && !out.empty()) out.back().end = at;
        at = eol + 1;
    }
    return out;
}

// What a condition's quantities become without it: identifiers (and
// "pixel_random()") replaced, and values read from the data passed through
// an expression of v.
struct Blind {
    std::map<std::string, std::string> names;
    std::string value;  // e.g. "max(v, 0.0)"; empty: values untouched
};

std::string escapeRegex(const std::string& s) {
    return std::regex_replace(s, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)");
}

std::string replaceNames(const std::string& text, const std::map<std::string, std::string>& names) {
    if (names.empty()) return text;
    std::string alternatives;
    for (const auto& [from, to] : names)
        alternatives += (alternatives.empty() ? "" : "|") + escapeRegex(from) + (std::isalnum(from.back()) ? "\\b" : "");
    const std::regex any("\\b(" + alternatives + ")");
    std::string out;
    std::size_t last = 0;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), any); it != std::sregex_iterator(); ++it) {
        out += text.substr(last, std::size_t(it->position(0)) - last) + names.at(it->str(1));
        last = std::size_t(it->position(0) + it->length(0));
    }
    return out + text.substr(last);
}

// The data-reading functions a blind wraps, with their argument types.
const std::vector<std::pair<std::string, std::string>> kValueReads = {
    {"sample_volume", "vec3"}, {"sample_nearest", "vec3"}, {"sample_trilinear", "vec3"}, {"voxel_value", "ivec3"}};

// The block's text through the blind; helpers for wrapped reads in *helpers.
std::string blindBlock(const std::string& block, const Blind& blind, const std::set<std::string>& defined,
                       std::string* helpers) {
    std::string out = replaceNames(block, blind.names);
    if (blind.value.empty()) return out;
    for (const auto& [read, type] : kValueReads) {
        if (defined.count(read) || !std::regex_search(out, std::regex("\\b" + read + R"(\s*\()"))) continue;
        out = std::regex_replace(out, std::regex("\\b" + read + R"(\s*\()"), "voxlab_blind_" + read + "(");
        const std::string helper = "float voxlab_blind_" + read + "(" + type + " x) { float v = " + read +
                                   "(x); return " + blind.value + "; }\n";
        if (helpers->find(helper) == std::string::npos) *helpers += helper;
    }
    if (!defined.count("transfer_function") && std::regex_search(out, std::regex(R"(\btransfer_function\s*\()"))) {
        out = std::regex_replace(out, std::regex(R"(\btransfer_function\s*\()"), "voxlab_blind_transfer_function(");
        const std::string helper = "vec4 voxlab_blind_transfer_function(float v) { return transfer_function(" +
                                   blind.value + "); }\n";
        if (helpers->find(helper) == std::string::npos) *helpers += helper;
    }
    return out;
}

// The stage's GLSL with `function`'s solution blocks through the blind;
// empty when nothing changes.
// Whether the replacements of `blind` can be compiled where `function` is
// defined: the step and the camera are declared by voxlab/ray.glsl, which
// the file must include, and a ray's fields need a Ray named ray.
bool blindFits(const Blind& blind, const std::string& text, const SolutionBlock& b) {
    for (const auto& [from, to] : blind.names) {
        if (std::regex_search(to, std::regex(R"(\bu_step|\bu_cam_|\bray\.)")) &&
            text.find("#include \"voxlab/ray.glsl\"") == std::string::npos)
            return false;
        if (to.find("ray.") != std::string::npos &&
            text.substr(b.functionStart, b.begin - b.functionStart).find("Ray ray") == std::string::npos)
            return false;
    }
    return true;
}

// The stage's GLSL with `function`'s solution blocks through the blind;
// empty when nothing changes.
std::map<std::string, std::string> blindFunction(const StageManifest& m, const std::string& function, const Blind& blind) {
    std::set<std::string> defined(m.functions.begin(), m.functions.end());
    std::map<std::string, std::string> changed;
    for (const std::string& file : m.files) {
        if (!isGlslFile(file)) continue;
        const std::string original = readText(kReference / m.stage / file);
        std::string text = original, helpers;
        const std::vector<SolutionBlock> blocks = solutionBlocks(text);
        std::size_t insertAt = std::string::npos;
        for (auto b = blocks.rbegin(); b != blocks.rend(); ++b) {
            if (b->function != function || !blindFits(blind, original, *b)) continue;
            text.replace(b->begin, b->end - b->begin, blindBlock(text.substr(b->begin, b->end - b->begin), blind, defined, &helpers));
            insertAt = b->functionStart;
        }
        if (insertAt != std::string::npos) text.insert(insertAt, helpers);
        if (text != original) changed[file] = text;
    }
    return changed;
}

// The generic blind of a condition, if it has one. `named` are the stage's
// conditions (an interpolation mode is read as another one the stage names).
std::optional<Blind> blindFor(const std::string& condition, const StageManifest& m, const std::set<std::string>& named) {
    if (condition == "signed") return Blind{{}, "max(v, 0.0)"};
    if (condition == "zeros") return Blind{{}, "(v == 0.0 ? u_value_range.y : v)"};
    if (condition == "spacing")
        return Blind{{{"u_step", "u_step_units"},
                      {"u_step_units", "u_step"},
                      {"u_min_spacing", "1.0"},
                      {"u_spacing", "(u_spacing / u_min_spacing)"},
                      {"u_slice_spacing", "(u_slice_spacing / u_min_spacing)"},
                      {"u_volume_extent", "(u_volume_extent / u_min_spacing)"}},
                     ""};
    if (condition == "step") return Blind{{{"u_step", "u_min_spacing"}, {"u_min_spacing", "u_step"}, {"u_step_units", "1.0"}}, ""};
    if (condition == "jitter") return Blind{{{"pixel_random()", "0.5"}}, ""};
    if (condition == "early_termination") return Blind{{{"u_early_termination", "2.0"}}, ""};
    if (condition.rfind("parameter:", 0) == 0) {
        const std::string name = condition.substr(10), type = uniformType(stageCode(m), name);
        if (type.empty()) return std::nullopt;
        return Blind{{{"u_" + name, type == "float" ? "0.0" : type == "int" ? "0" : "false"}}, ""};
    }
    if (condition.rfind("interpolation:", 0) == 0) {
        const int mode = int(parseInterpolation(condition.substr(14)));
        int other = mode == 0 ? 1 : 0;
        for (const std::string& c : named)
            if (c.rfind("interpolation:", 0) == 0 && c != condition) other = int(parseInterpolation(c.substr(14)));
        const std::string k = std::to_string(mode);
        return Blind{{{"u_interpolation", "(u_interpolation == " + k + " ? " + std::to_string(other) + " : u_interpolation)"}}, ""};
    }
    if (condition == "perspective") return Blind{{{"ray.direction", "u_cam_forward"}, {"u_cam_forward", "ray.direction"}}, ""};
    if (condition == "orthographic") return Blind{{{"ray.origin", "u_cam_position"}, {"u_cam_position", "ray.origin"}}, ""};
    return std::nullopt;  // background, clip planes
}

// The stage's mutants (mutants.json) that name `condition` among theirs.
std::vector<Witness> taggedMutants(const StageManifest& m, const std::string& condition) {
    std::vector<Witness> out;
    const fs::path file = kReference / m.stage / "mutants.json";
    if (!fs::exists(file)) return out;
    for (const nlohmann::json& j : nlohmann::json::parse(readText(file)).value("mutants", nlohmann::json::array())) {
        const std::vector<std::string> named = j.value("conditions", std::vector<std::string>{});
        if (std::find(named.begin(), named.end(), condition) == named.end()) continue;
        const std::string path = j.at("file"), name = path.substr(path.find('/') + 1);
        std::string text = readText(kReference / path);
        const std::size_t at = text.find(j.at("find").get<std::string>());
        if (at == std::string::npos) throw std::runtime_error(m.stage + ": mutant " + j.value("name", "") + " does not apply");
        text.replace(at, j.at("find").get<std::string>().size(), j.at("replace").get<std::string>());
        out.push_back({"mutant " + j.value("name", ""), {{name, text}}});
    }
    return out;
}

std::vector<Witness> witnessesFor(const StageManifest& m, const std::string& condition, const std::set<std::string>& named) {
    std::vector<Witness> out;
    // One quantity of one function at a time: each is one mistake.
    if (const std::optional<Blind> blind = blindFor(condition, m, named))
        for (const std::string& f : m.functions) {
            if (!blind->value.empty()) {
                std::map<std::string, std::string> files = blindFunction(m, f, Blind{{}, blind->value});
                if (!files.empty()) out.push_back({"v -> " + blind->value + " in " + f + "()", files});
            }
            for (const auto& [from, to] : blind->names) {
                std::map<std::string, std::string> files = blindFunction(m, f, Blind{{{from, to}}, ""});
                if (!files.empty()) out.push_back({from + " -> " + to + " in " + f + "()", files});
            }
        }
    if (condition.rfind("clip_planes:", 0) == 0) out.push_back({"the scene without its clip planes", {}, false, true});
    for (Witness& w : taggedMutants(m, condition)) out.push_back(w);
    if (out.empty()) out.push_back({"the starter code's stub", {}, true});
    for (Witness& w : out) w.key = w.stub || w.withoutClipPlanes || w.label.rfind("mutant ", 0) == 0 ? w.label : condition + " " + w.label;
    return out;
}

// Every condition the stage has: by rule and by its manifest.
std::set<std::string> stageConditions(const StageManifest& m) {
    std::set<std::string> out = conditionsByRule(m);
    out.insert(m.conditions.begin(), m.conditions.end());
    return out;
}

// An image as the grader compares it: 8-bit channels, as read from a PNG.
Image asGraded(const Image& image) {
    Image out(image.width, image.height);
    for (std::size_t i = 0; i < out.rgba.size(); ++i)
        out.rgba[i] = i % 4 == 3 ? 1.0f : float(toByte(image.rgba[i])) / 255.0f;
    return out;
}

// Renders and checks witnesses against the reference, compared as the
// grader compares them, and remembers every verdict: the worst ratio of a
// metric to its bound (a check: 2 when some case fails, else 0).
class ConditionLab {
public:
    ConditionLab()
        : context_(createHeadlessContext()),
          scratch_(fs::path(::testing::TempDir()) / ("voxlab_conditions_" + std::to_string(getpid()))) {
        fs::remove_all(scratch_);
        volumeCache();  // made before the lab, so destroyed after its engines
        reference_ = std::make_unique<RenderEngine>(rendererRegistry(), kReference.string());
    }
    ~ConditionLab() { fs::remove_all(scratch_); }

    double ratio(const StageManifest& m, const Witness& w, const std::string& item) {
        const std::string key = m.stage + "|" + w.key + "|" + item;
        auto found = verdicts_.find(key);
        if (found != verdicts_.end()) return found->second;
        double r = 0.0;
        for (const GradedScene& s : m.scenes)
            if (s.name == item) r = sceneRatio(m, w, s);
        for (const GradedCheck& c : m.checks)
            if (c.name == item) r = checkRatio(m, w, c.name);
        return verdicts_[key] = r;
    }

private:
    // The implementation root of a witness: its stage folder in a folder of
    // its own (every other stage comes from the reference).
    std::string root(const StageManifest& m, const Witness& w) {
        if (!w.stub && w.files.empty()) return kReference.string();
        const fs::path root = scratch_ / std::to_string(roots_++), folder = root / m.stage;
        fs::create_directories(folder);
        const fs::path from = w.stub ? fs::path(VOXLAB_SOURCE_DIR) / "assignments" / m.stage : kReference / m.stage;
        for (const auto& e : fs::directory_iterator(from))
            if (e.is_regular_file()) fs::copy_file(e.path(), folder / e.path().filename());
        for (const auto& [file, text] : w.files) std::ofstream(folder / file, std::ios::binary | std::ios::trunc) << text;
        return root.string();
    }

    RenderEngine& engineFor(const StageManifest& m, const Witness& w) {
        if (!w.stub && w.files.empty()) return *reference_;
        const std::string key = m.stage + "|" + w.key;
        if (key != current_) {
            engine_.reset();
            engine_ = std::make_unique<RenderEngine>(rendererRegistry(), root(m, w));
            current_ = key, currentRoot_ = engine_->implementationRoot();
        }
        return *engine_;
    }

    Image render(RenderEngine& engine, const GradedScene& graded, bool withoutClipPlanes) {
        Scene scene = gradingSceneFor(graded, volumeCache(), engine);
        if (withoutClipPlanes) scene.clipPlanes.clear();
        return asGraded(engine.render(scene));
    }

    double sceneRatio(const StageManifest& m, const Witness& w, const GradedScene& s) {
        auto expected = expected_.find(s.scenePath);
        if (expected == expected_.end()) expected = expected_.emplace(s.scenePath, render(*reference_, s, false)).first;
        const Image got = render(engineFor(m, w), s, w.withoutClipPlanes);
        return toleranceRatio(compareForGrading(expected->second, got, s.tolerance), s.tolerance);
    }

    double checkRatio(const StageManifest& m, const Witness& w, const std::string& check) {
        if (!w.stub && w.files.empty()) return 0.0;  // the reference's code, scenes drawn differently
        auto expected = expectedChecks_.find(check);
        if (expected == expectedChecks_.end()) expected = expectedChecks_.emplace(check, runFunctionCheck(check, "")).first;
        engineFor(m, w);  // makes the witness's root
        try {
            const CheckComparison c = compareFunctionCheck(check, expected->second, runFunctionCheck(check, currentRoot_));
            return c.failed > 0 ? 2.0 : 0.0;
        } catch (const NotImplemented&) {
            return 2.0;
        }
    }

    std::unique_ptr<GlContext> context_;
    fs::path scratch_;
    int roots_ = 0;
    std::unique_ptr<RenderEngine> reference_, engine_;
    std::string current_, currentRoot_;
    std::map<std::string, Image> expected_;
    std::map<std::string, nlohmann::json> expectedChecks_;
    std::map<std::string, double> verdicts_;
};

ConditionLab& conditionLab() {
    static ConditionLab lab;
    return lab;
}

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

// The items (scenes, then checks) that have `condition`.
std::vector<std::string> coveringItems(const StageManifest& m, const std::string& condition) {
    std::vector<std::string> out;
    for (const GradedScene& s : m.scenes)
        if (sceneConditions(s).count(condition)) out.push_back(s.name);
    for (const GradedCheck& c : m.checks)
        if (std::count(c.conditions.begin(), c.conditions.end(), condition)) out.push_back(c.name);
    return out;
}

struct ConditionShown {
    std::string stage, condition, witness, item;
    double ratio = 0.0;
};

// What R6 finds missing in one stage; *shown gets, for each condition and
// witness, the first item that shows it.
std::vector<std::string> conditionProblems(const StageManifest& m, std::vector<ConditionShown>* shown = nullptr) {
    std::vector<std::string> problems;
    const std::string where = m.stage + ": ";
    const std::set<std::string> named = stageConditions(m);
    for (const std::string& c : named) {
        if (!knownCondition(c)) {
            problems.push_back(where + "unknown condition '" + c + "' (test_stage_coverage.cpp lists them)");
            continue;
        }
        const std::vector<std::string> covering = coveringItems(m, c);
        if (covering.empty()) {
            problems.push_back(where + c + ": no scene or check has this condition");
            continue;
        }
        for (const Witness& w : witnessesFor(m, c, named)) {
            ConditionShown found{m.stage, c, w.label, "", 0.0};
            for (const std::string& item : covering)
                if ((found.ratio = conditionLab().ratio(m, w, item)) > 1.0) {
                    found.item = item;
                    break;
                }
            if (found.item.empty())
                problems.push_back(where + c + ": " + w.label + " changes none of its items (" + joined(covering) +
                                   ") beyond the tolerance");
            else if (shown)
                shown->push_back(found);
        }
    }
    return problems;
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
    // The only signed scene of a stage, the only anisotropic one, a
    // function's second item. (The jitter scenes, the slab's anisotropic
    // scene and the half-space check had this part before the conditions'
    // scenes came; TakingAConditionSceneAwayFailsTheConditionRule shows
    // those.)
    for (const char* item : {"average/headsq_hu_oblique", "firsthit/headsq_hu_skin_depth", "texslice2d/headsq_oblique",
                             "splat/headsq_hu_anisotropic", "composite/tooth_back_to_front"})
        EXPECT_TRUE(critical.count(item)) << "removing " << item << " should break the coverage rules";
}

TEST(StageCoverage, EveryConditionIsShownByAGradedItem) {
    std::vector<ConditionShown> shown;
    for (const StageManifest& m : gradedManifests())
        for (const std::string& p : conditionProblems(m, &shown)) ADD_FAILURE() << p;
    for (const ConditionShown& s : shown)
        std::printf("%-16s %-32s %-44s %-34s %6.2f\n", s.stage.c_str(), s.condition.c_str(), s.witness.c_str(),
                    s.item.c_str(), s.ratio);
    EXPECT_GE(shown.size(), 60u);
}

// The generic blinds are the reference wherever their condition is absent:
// every scene without the condition passes with each of them (heavy: every
// scene of a stage once per blind).
TEST(StageCoverage, ABlindLeavesTheScenesWithoutItsConditionAlone) {
    int compared = 0;
    for (const StageManifest& m : gradedManifests()) {
        const std::set<std::string> named = stageConditions(m);
        for (const std::string& c : named) {
            if (!knownCondition(c) || !blindFor(c, m, named)) continue;
            for (const Witness& w : witnessesFor(m, c, named)) {
                if (w.stub || w.withoutClipPlanes || w.label.rfind("mutant ", 0) == 0) continue;
                for (const GradedScene& s : m.scenes) {
                    if (sceneConditions(s).count(c)) continue;
                    ++compared;
                    EXPECT_LE(conditionLab().ratio(m, w, s.name), 1.0)
                        << m.stage << "/" << s.name << " has no " << c << ", yet " << w.label << " fails it";
                }
            }
        }
    }
    std::printf("%d scenes without a condition compared with its blinds\n", compared);
}

// Taking away the one scene that shows a condition fails R6 for it.
TEST(StageCoverage, TakingAConditionSceneAwayFailsTheConditionRule) {
    const std::vector<std::pair<std::string, std::string>> sole = {
        {"minip/fuel_uncropped", "zeros"},
        {"composite/fuel_preclassified_nearest", "interpolation:nearest"},
        {"composite/tooth_white_early_termination", "background"},
        {"composite/headsq_hu_jitter_coarse", "spacing"},
        {"cutting_plane/clip_mip", "clip_planes:mip"},
    };
    for (const auto& [item, condition] : sole) {
        const std::string stage = item.substr(0, item.find('/')), name = item.substr(item.find('/') + 1);
        StageManifest fewer = loadStageManifest(kReference.string(), stage);
        EXPECT_TRUE(conditionProblems(fewer).empty()) << item;
        const auto before = fewer.scenes.size();
        fewer.scenes.erase(std::remove_if(fewer.scenes.begin(), fewer.scenes.end(),
                                          [&](const GradedScene& s) { return s.name == name; }),
                           fewer.scenes.end());
        ASSERT_EQ(fewer.scenes.size() + 1, before) << item;
        std::string problems;
        for (const std::string& p : conditionProblems(fewer)) problems += p + "\n";
        std::printf("without %s:\n%s", item.c_str(), problems.c_str());
        EXPECT_NE(problems.find(stage + ": " + condition + ":"), std::string::npos)
            << "removing " << item << " should leave " << condition << " unshown";
    }
}

// The rules read the conditions from the code (nothing is rendered here).
TEST(StageCoverage, ConditionRulesReadTheCode) {
    auto of = [](const std::string& stage) { return conditionsByRule(loadStageManifest(kReference.string(), stage)); };
    const std::set<std::string> composite = of("composite");
    for (const char* c : {"signed", "spacing", "step", "interpolation:nearest", "jitter", "early_termination", "background"})
        EXPECT_TRUE(composite.count(c)) << "composite: " << c;
    EXPECT_TRUE(of("slab_mip").count("step"));
    EXPECT_TRUE(of("slab_mip").count("parameter:thickness"));
    EXPECT_TRUE(of("cutting_plane").count("clip_planes:mip"));
    EXPECT_TRUE(of("cutting_plane").count("clip_planes:splat"));
    EXPECT_FALSE(of("cutting_plane").count("clip_planes:shearwarp"));  // shear-warp draws no clip planes
    EXPECT_FALSE(of("gradient").count("step"));  // drawn by the slicer, which takes no steps
    EXPECT_FALSE(of("mip").count("jitter"));
    for (const StageManifest& m : gradedManifests()) {
        std::string list;
        for (const std::string& c : stageConditions(m)) {
            EXPECT_TRUE(knownCondition(c)) << m.stage << ": " << c;
            list += " " + c;
        }
        std::printf("%-18s%s\n", m.stage.c_str(), list.c_str());
    }
}

// A blind changes one function's solution, and only the condition's
// quantities in it.
TEST(StageCoverage, ABlindChangesOneSolutionAndOnlyItsConditionsQuantities) {
    const StageManifest slab = loadStageManifest(kReference.string(), "slab_mip");
    const auto files = blindFunction(slab, "clip_to_slab", *blindFor("step", slab, stageConditions(slab)));
    ASSERT_EQ(files.size(), 1u);
    const std::string before = readText(kReference / "slab_mip/slab_mip.glsl"), after = files.at("slab_mip.glsl");
    EXPECT_NE(after.find("float h = 0.5 * u_thickness * u_step;"), std::string::npos) << after;
    EXPECT_NE(after.find("u_offset * u_step * n;"), std::string::npos) << after;
    EXPECT_EQ(before.substr(0, before.find("BEGIN SOLUTION")), after.substr(0, after.find("BEGIN SOLUTION")));
    EXPECT_EQ(before.substr(before.find("END SOLUTION")), after.substr(after.find("END SOLUTION")));

    const StageManifest minip = loadStageManifest(kReference.string(), "minip");
    const std::string zeros = blindFunction(minip, "minip_ray", *blindFor("zeros", minip, {})).at("minip.glsl");
    EXPECT_NE(zeros.find("float voxlab_blind_sample_volume(vec3 x) { float v = sample_volume(x); return (v == 0.0 ? "
                         "u_value_range.y : v); }\nfloat minip_ray("),
              std::string::npos)
        << zeros;
    EXPECT_NE(zeros.find("min(minimum, voxlab_blind_sample_volume(sample_position(ray, m)))"), std::string::npos);
    EXPECT_TRUE(blindFunction(minip, "minip_ray", *blindFor("jitter", minip, {})).empty());  // no such quantity

    const StageManifest composite = loadStageManifest(kReference.string(), "composite");
    const std::string jitter = blindFunction(composite, "jitter_start", *blindFor("spacing", composite, {})).at("composite.glsl");
    EXPECT_NE(jitter.find("ray.t_entry += (pixel_random() - 0.5) * u_step_units;"), std::string::npos);
    EXPECT_NE(jitter.find("opacity_correction(c.a, u_step_units)"), std::string::npos);  // another function's
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
