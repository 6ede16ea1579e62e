// voxlab: stage manifests, grading metrics and credit (see grading.h).
#include "voxlab/grading.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "../scene/json_text.h"
#include "voxlab/error.h"
#include "voxlab/flip.h"
#include "voxlab/image_metrics.h"
#include "voxlab/render_engine.h"
#include "voxlab/scene.h"
#include "voxlab/volume.h"
#include "voxlab/stage_library.h"

namespace voxlab {

namespace {

using nlohmann::json;

double number(const json& j, const std::string& key, double fallback, const std::string& where) {
    if (!j.contains(key)) return fallback;
    if (!j.at(key).is_number()) throw Error(where + ": " + key + ": expected a number");
    return j.at(key).get<double>();
}

std::string text(const json& j, const std::string& key, const std::string& where, bool required) {
    if (!j.contains(key)) {
        if (required) throw Error(where + ": " + key + ": missing");
        return "";
    }
    if (!j.at(key).is_string()) throw Error(where + ": " + key + ": expected a string");
    return j.at(key).get<std::string>();
}

// Every key of an object is one of `known`: a misspelt key would otherwise
// be ignored in silence (a "tolerances" that loosens nothing).
void onlyKeys(const json& j, const std::string& where, std::initializer_list<const char*> known) {
    for (const auto& item : j.items()) {
        bool ok = false;
        for (const char* k : known) ok = ok || item.key() == k;
        if (ok) continue;
        std::string list;
        for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
        throw Error(where + ": unknown key '" + item.key() + "' (known: " + list + ")");
    }
}

}  // namespace

Tolerance overTolerance(const Tolerance& base, const json& j, const std::string& where) {
    if (!j.is_object()) throw Error(where + ": expected an object");
    onlyKeys(j, where, {"max_difference", "max_fraction", "min_ssim", "max_flip", "cluster_difference", "max_cluster",
                        "shift", "why"});
    Tolerance t = base;
    t.maxDifference = number(j, "max_difference", t.maxDifference, where);
    t.maxFraction = number(j, "max_fraction", t.maxFraction, where);
    t.minSsim = number(j, "min_ssim", t.minSsim, where);
    t.maxFlip = number(j, "max_flip", t.maxFlip, where);
    t.clusterDifference = number(j, "cluster_difference", t.clusterDifference, where);
    t.maxCluster = number(j, "max_cluster", t.maxCluster, where);
    t.shift = int(number(j, "shift", t.shift, where));
    if (t.shift < 0 || t.shift > 1) throw Error(where + ": shift must be 0 or 1 (pixels)");
    if (!(t.maxDifference >= 0 && t.maxFraction >= 0 && t.maxFraction < 1 && t.minSsim < 1 && t.maxFlip > 0 &&
          t.clusterDifference >= 0 && t.maxCluster >= 1))
        throw Error(where + ": tolerances out of range");
    return t;
}

namespace {

std::vector<std::string> stringList(const json& j, const char* key, const std::string& path) {
    std::vector<std::string> list;
    if (!j.contains(key)) return list;
    if (!j.at(key).is_array()) throw Error(path + ": " + key + ": expected an array of names");
    for (const json& e : j.at(key)) {
        if (!e.is_string()) throw Error(path + ": " + key + ": expected an array of names");
        list.push_back(e.get<std::string>());
    }
    return list;
}

bool isSourceFile(const std::filesystem::path& p) {
    const std::string ext = p.extension().string();
    return ext == ".glsl" || ext == ".frag" || ext == ".vert" || ext == ".cpp";
}

// The manifest's "files", or the source files beside it; plain names only.
std::vector<std::string> stageFiles(const json& j, const std::filesystem::path& folder, const std::string& path) {
    std::vector<std::string> files = stringList(j, "files", path);
    if (!j.contains("files")) {
        std::error_code ec;
        for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
            if (entry.is_regular_file() && isSourceFile(entry.path())) files.push_back(entry.path().filename());
        std::sort(files.begin(), files.end());
    }
    for (const std::string& f : files)
        if (f.empty() || f[0] == '.' || f.find_first_of("/\\") != std::string::npos || !isSourceFile(f))
            throw Error(path + ": files: '" + f + "' is not a plain .glsl, .frag, .vert or .cpp file name");
    return files;
}

}  // namespace

namespace {

// Calls each(object, where) for every element of the array j[key] (none
// when the key is missing); anything but an array of objects is an error.
template <class Each>
void forEachObject(const json& j, const char* key, const std::string& path, Each each) {
    if (!j.contains(key)) return;
    if (!j.at(key).is_array()) throw Error(path + ": " + key + ": expected an array");
    for (std::size_t i = 0; i < j.at(key).size(); ++i) {
        const std::string where = path + ": " + key + "[" + std::to_string(i) + "]";
        if (!j.at(key)[i].is_object()) throw Error(where + ": expected an object");
        each(j.at(key)[i], where);
    }
}

std::vector<GradedScene> readScenes(const json& j, const std::filesystem::path& folder, const std::string& path) {
    std::vector<GradedScene> scenes;
    const Tolerance stageWide = j.contains("tolerance") ? overTolerance({}, j.at("tolerance"), path + ": tolerance") : Tolerance{};
    forEachObject(j, "scenes", path, [&](const json& s, const std::string& where) {
        onlyKeys(s, where, {"name", "scene", "weight", "hidden", "tolerance", "functions", "about"});
        GradedScene g;
        g.tolerance = stageWide;
        g.name = text(s, "name", where, true);
        g.scenePath = (folder / text(s, "scene", where, true)).lexically_normal().string();
        g.weight = number(s, "weight", 1.0, where);
        if (s.contains("hidden") && !s.at("hidden").is_boolean()) throw Error(where + ": hidden: expected true or false");
        g.hidden = s.value("hidden", false);
        if (s.contains("tolerance")) g.tolerance = overTolerance(stageWide, s.at("tolerance"), where + ".tolerance");
        g.functions = stringList(s, "functions", where);
        g.about = text(s, "about", where, false);
        if (g.name.empty() || g.name.find_first_of("/\\. ") != std::string::npos)
            throw Error(where + ": name: use letters, digits and underscores");
        scenes.push_back(g);
    });
    return scenes;
}

std::vector<GradedCheck> readChecks(const json& j, const std::string& path) {
    std::vector<GradedCheck> checks;
    forEachObject(j, "checks", path, [&](const json& c, const std::string& where) {
        onlyKeys(c, where, {"name", "weight", "functions", "conditions"});
        checks.push_back({text(c, "name", where, true), number(c, "weight", 1.0, where), stringList(c, "functions", where),
                          stringList(c, "conditions", where)});
    });
    return checks;
}

std::vector<StageHint> readHints(const json& j, const StageManifest& m, const std::string& path) {
    std::vector<StageHint> hints;
    forEachObject(j, "hints", path, [&](const json& h, const std::string& where) {
        onlyKeys(h, where, {"failed", "hints"});
        StageHint hint{stringList(h, "failed", where), stringList(h, "hints", where)};
        for (const std::string& name : hint.failed) {
            bool known = false;
            for (const GradedScene& s : m.scenes) known = known || s.name == name;
            for (const GradedCheck& c : m.checks) known = known || c.name == name;
            if (!known) throw Error(where + ": failed: '" + name + "' is not a scene or check of this stage");
        }
        std::sort(hint.failed.begin(), hint.failed.end());
        hints.push_back(hint);
    });
    return hints;
}

// Items name only the stage's functions.
void checkItemFunctions(const StageManifest& m, const std::string& path) {
    for (const std::string& f : m.functions)
        if (f.empty() || f.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") !=
                             std::string::npos)
            throw Error(path + ": functions: '" + f + "' is not a function name");
    auto known = [&](const std::vector<std::string>& names, const std::string& where) {
        for (const std::string& n : names)
            if (std::find(m.functions.begin(), m.functions.end(), n) == m.functions.end())
                throw Error(path + ": " + where + ": functions: '" + n + "' is not one of the stage's functions");
    };
    for (const GradedScene& s : m.scenes) known(s.functions, "scene " + s.name);
    for (const GradedCheck& c : m.checks) known(c.functions, "check " + c.name);
    if (m.points > 0 && m.functions.empty())
        throw Error(path + ": functions: required for a graded stage (what students write)");
}

}  // namespace

StageManifest loadStageManifest(const std::string& root, const std::string& stage) {
    const std::filesystem::path folder = std::filesystem::path(root) / stage;
    const std::string path = (folder / "grading.json").string();
    if (!std::filesystem::exists(path)) throw Error(path + ": no such file (stage '" + stage + "' has no manifest)");
    const json j = json_text::readJsonFile(path);
    if (!j.is_object()) throw Error(path + ": expected an object");
    onlyKeys(j, path, {"title", "order", "about", "points", "tolerance", "scenes", "checks", "files", "cpp_functions",
                       "functions", "requires", "hints", "conditions"});
    StageManifest m;
    m.stage = stage;
    m.title = text(j, "title", path, true);
    if (!j.contains("order") || !j.at("order").is_number_integer())
        throw Error(path + ": order: required, a whole number (the stage's place in teaching order)");
    m.order = j.at("order").get<int>();
    m.about = text(j, "about", path, false);
    m.points = number(j, "points", 10.0, path);
    if (!(m.points >= 0)) throw Error(path + ": points: must be >= 0");
    m.scenes = readScenes(j, folder, path);
    m.checks = readChecks(j, path);
    m.files = stageFiles(j, folder, path);
    m.cppFunctions = stringList(j, "cpp_functions", path);
    for (const std::string& f : m.cppFunctions)
        if (!isStageFunction(f)) throw Error(path + ": cpp_functions: '" + f + "' is not a C++ stage function");
    m.functions = stringList(j, "functions", path);
    m.conditions = stringList(j, "conditions", path);
    m.requires = stringList(j, "requires", path);
    checkItemFunctions(m, path);
    m.hints = readHints(j, m, path);
    return m;
}

namespace {

// Whether `name` occurs in `text` as a whole word followed by "(" (spaces
// allowed between): a definition or a call. A scan, not std::regex: the
// grader asks it for every function of every stage several times at each
// start (16 ms a time with std::regex, 2.7 ms with the scan).
bool namesACall(const std::string& text, const std::string& name) {
    const auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
        if (at > 0 && word(text[at - 1])) continue;
        std::size_t next = at + name.size();
        while (next < text.size() && std::isspace(static_cast<unsigned char>(text[next]))) ++next;
        if (next < text.size() && text[next] == '(') return true;
    }
    return false;
}

}  // namespace

void checkStageFunctions(const StageManifest& m, const std::string& root) {
    const std::filesystem::path folder = std::filesystem::path(root) / m.stage;
    const std::string path = (folder / "grading.json").string();
    std::string sources;
    for (const std::string& f : m.files) {
        std::ifstream in(folder / f, std::ios::binary);
        if (!in) throw Error(path + ": files: cannot read " + f);
        sources += json_text::readCappedText(in, (folder / f).string()) + "\n";
    }
    for (const std::string& f : m.functions)
        if (!namesACall(sources, f))
            throw Error(path + ": functions: '" + f + "' is not defined in the stage's files");
}

std::vector<std::string> hintsFor(const StageManifest& manifest, const std::vector<std::string>& failedSorted,
                                  const std::vector<std::string>& blocked) {
    std::vector<std::string> out;
    if (failedSorted.empty()) return out;
    for (const StageHint& h : manifest.hints)
        if (h.failed == failedSorted && std::none_of(h.failed.begin(), h.failed.end(), [&](const std::string& item) {
                return std::count(blocked.begin(), blocked.end(), item) > 0;
            }))
            for (const std::string& text : h.hints)
                if (std::find(out.begin(), out.end(), text) == out.end()) out.push_back(text);
    return out;
}

std::vector<StageManifest> stageManifests(const std::string& root) {
    std::vector<StageManifest> manifests;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(root, ec))
        if (entry.is_directory() && std::filesystem::exists(entry.path() / "grading.json"))
            manifests.push_back(loadStageManifest(root, entry.path().filename().string()));
    if (ec) throw Error(root + ": cannot list the stages: " + ec.message());
    for (const StageManifest& m : manifests) {
        checkStageFunctions(m, root);
        for (const std::string& r : m.requires)
            if (std::none_of(manifests.begin(), manifests.end(), [&](const StageManifest& o) { return o.stage == r; }))
                throw Error(root + "/" + m.stage + "/grading.json: requires: no stage '" + r + "'");
    }
    std::sort(manifests.begin(), manifests.end(), [](const StageManifest& a, const StageManifest& b) {
        return a.order != b.order ? a.order < b.order : a.stage < b.stage;
    });
    return manifests;
}

namespace {

// `from`'s value within `shift` pixels of each pixel that is closest to
// `to`'s value there (the largest channel difference decides).
Image closestWithin(const Image& from, const Image& to, int shift) {
    Image out(to.width, to.height);
    for (int y = 0; y < to.height; ++y)
        for (int x = 0; x < to.width; ++x) {
            const glm::vec4 target = to.at(x, y);
            glm::vec4 best = from.at(x, y);
            float bestDistance = std::numeric_limits<float>::infinity();
            for (int dy = -shift; dy <= shift; ++dy)
                for (int dx = -shift; dx <= shift; ++dx) {
                    const int u = std::clamp(x + dx, 0, to.width - 1), v = std::clamp(y + dy, 0, to.height - 1);
                    const glm::vec4 d = glm::abs(from.at(u, v) - target);
                    const float distance = std::max({d.r, d.g, d.b, d.a});
                    if (distance < bestDistance) bestDistance = distance, best = from.at(u, v);
                }
            out.set(x, y, best);
        }
    return out;
}

}  // namespace

ImageMetrics compareForGrading(const Image& expected, const Image& given, const Tolerance& tolerance,
                               Image* flipMap, Image* differenceMap) {
    if (expected.width != given.width || expected.height != given.height)
        throw Error("image size " + std::to_string(given.width) + "x" + std::to_string(given.height) +
                    " differs from the expected " + std::to_string(expected.width) + "x" +
                    std::to_string(expected.height));
    // With a shift, each image is matched against the other's closest value
    // nearby: what the submission lacks shows in the first pair, what it has
    // in excess in the second.
    const Image& submission = tolerance.shift > 0 ? closestWithin(given, expected, tolerance.shift) : given;
    const Image backward = tolerance.shift > 0 ? closestWithin(expected, given, tolerance.shift) : Image();
    ImageMetrics m;
    // Half a grey level of slack: PNG values are multiples of 1/255.
    const double over = (tolerance.maxDifference + 0.5) / 255.0, bad = (tolerance.clusterDifference + 0.5) / 255.0;
    const PixelDifference d = pixelDifference(expected, submission, over);
    m.fractionOver = d.fractionAbove;
    m.maxDifference = d.max * 255.0;
    m.largestCluster = largestCluster(expected, submission, bad);
    if (tolerance.shift > 0) {
        const PixelDifference back = pixelDifference(backward, given, over);
        m.fractionOver = std::max(m.fractionOver, back.fractionAbove);
        m.maxDifference = std::max(m.maxDifference, back.max * 255.0);
        m.largestCluster = std::max(m.largestCluster, largestCluster(backward, given, bad));
    }
    const SsimResult s = ssim(expected, submission);
    m.ssim = s.mean;
    m.ssimMin = s.min;
    const FlipResult f = flip(expected, submission);
    m.flipMean = f.mean;
    m.flipMax = f.max;
    m.psnr = psnr(expected, submission);
    if (flipMap) *flipMap = heatmap(f);
    if (differenceMap) {
        // |difference| amplified four times in grey; pixels over the bound in red.
        Image out(expected.width, expected.height);
        for (int y = 0; y < out.height; ++y)
            for (int x = 0; x < out.width; ++x) {
                const glm::vec4 a = glm::clamp(expected.at(x, y), 0.0f, 1.0f);
                const glm::vec4 b = glm::clamp(submission.at(x, y), 0.0f, 1.0f);
                const glm::vec3 delta = glm::abs(glm::vec3(a) - glm::vec3(b));
                const float worst = std::max({delta.r, delta.g, delta.b});
                const float grey = std::min(1.0f, 4.0f * worst);
                const bool over = worst * 255.0f > float(tolerance.maxDifference) + 0.5f;
                out.set(x, y, over ? glm::vec4(1.0f, 0.15f + 0.3f * (1 - grey), 0.1f, 1.0f)
                                   : glm::vec4(grey, grey, grey, 1.0f));
            }
        *differenceMap = out;
    }
    return m;
}

double toleranceRatio(const ImageMetrics& m, const Tolerance& t) {
    const double inf = std::numeric_limits<double>::infinity();
    const double pixels = t.maxFraction > 0 ? m.fractionOver / t.maxFraction : (m.fractionOver > 0 ? inf : 0.0);
    const double structure = (1.0 - m.ssim) / (1.0 - t.minSsim);
    const double flipRatio = m.flipMean / t.maxFlip;
    const double cluster = m.largestCluster / t.maxCluster;
    return std::max({pixels, structure, flipRatio, cluster, 0.0});
}

double creditForRatio(double ratio) {
    if (!(ratio <= 3.0)) return 0.0;  // NaN too
    if (ratio <= 1.0) return 1.0;
    return (3.0 - ratio) / 4.0;
}

double creditForFailedCases(double failedFraction) {
    if (!(failedFraction >= 0.0)) return 0.0;
    if (failedFraction == 0.0) return 1.0;
    return 0.5 * std::max(0.0, 1.0 - failedFraction / 0.1);
}

Scene gradingSceneFor(const GradedScene& graded, std::map<std::string, Volume>& volumes, RenderEngine& engine) {
    Scene scene = Scene::load(graded.scenePath);
    scene.skipEmptySpace = false;
    auto found = volumes.find(scene.dataset);
    if (found == volumes.end()) found = volumes.emplace(scene.dataset, loadVolume(scene.dataset)).first;
    engine.setVolume(found->second);
    return scene;
}

nlohmann::json sceneVerdict(const ImageMetrics& m, const Tolerance& tolerance, double* credit) {
    const double ratio = toleranceRatio(m, tolerance);
    *credit = creditForRatio(ratio);
    char line[240];
    std::snprintf(line, sizeof line,
                  "%.2f%% of pixels off by more than %g levels, largest patch off by more than %g: %d px, "
                  "SSIM %.4f, FLIP %.4f",
                  100.0 * m.fractionOver, tolerance.maxDifference, tolerance.clusterDifference, m.largestCluster,
                  m.ssim, m.flipMean);
    return {{"metrics", toJson(m)}, {"status", ratio <= 1.0 ? "passed" : "failed"}, {"message", line}};
}

nlohmann::json toJson(const ImageMetrics& m) {
    json j = {{"fraction_over", m.fractionOver}, {"max_difference", m.maxDifference},
              {"largest_cluster", m.largestCluster}, {"ssim", m.ssim},
              {"ssim_min", m.ssimMin}, {"flip_mean", m.flipMean}, {"flip_max", m.flipMax}};
    if (std::isfinite(m.psnr)) j["psnr"] = m.psnr;
    else j["psnr"] = nullptr;  // identical
    return j;
}

nlohmann::json toJson(const Tolerance& t) {
    json j = {{"max_difference", t.maxDifference}, {"max_fraction", t.maxFraction}, {"min_ssim", t.minSsim},
              {"max_flip", t.maxFlip}, {"cluster_difference", t.clusterDifference}, {"max_cluster", t.maxCluster}};
    if (t.shift > 0) j["shift"] = t.shift;
    return j;
}

}  // namespace voxlab
