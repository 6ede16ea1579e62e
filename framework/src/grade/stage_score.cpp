// voxlab grader: scoring one stage's outputs against the expected ones.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "stage_job.h"
#include "voxlab/atomic_file.h"
#include "voxlab/error.h"
#include "voxlab/function_checks.h"
#include "voxlab/image.h"
#include "voxlab/scene.h"
#include "voxlab/untrusted_text.h"

namespace voxlab::grading {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::optional<json> readJson(const fs::path& path) {
    std::ifstream in(path);
    if (!in) return std::nullopt;
    try {
        return json::parse(in);
    } catch (const json::exception&) {
        return std::nullopt;
    }
}

void replaceAll(std::string& s, const std::string& from, const std::string& to) {
    if (from.empty()) return;
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
        s.replace(at, from.size(), to);
}

// Compiler logs name files by absolute path; a student reads them relative
// to their own folder ("mip/mip.glsl:14:9"), framework files relative to
// the project ("shaders/voxlab/ray.glsl"). What the stage's build and run
// printed is the submission's text: it comes back as safe text, at most
// `maxBytes` long (untrusted_text.h).
std::string relativePaths(std::string text, const StageRun& run, std::size_t maxBytes = kMaxLogBytes) {
    replaceAll(text, (fs::path(run.workDir) / "impl").string() + "/", "");
    replaceAll(text, fs::path(run.implementationRoot).lexically_normal().string() + "/", "");
    replaceAll(text, fs::path(projectRoot()).lexically_normal().string() + "/", "");
    return safeText(text, maxBytes);
}

std::string firstLine(const std::string& s) { return s.substr(0, s.find('\n')); }

// The expected image, copied into the report beside the submission's.
void copyIntoReport(const fs::path& from, const fs::path& to) {
    std::ifstream in(from, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    writeFileAtomically(to.string(), bytes.str());
}

// The line of a compiler log that says what is wrong: the first with
// "error", else the first.
std::string errorLine(const std::string& log) {
    std::istringstream in(log);
    for (std::string line; std::getline(in, line);)
        if (line.find("error") != std::string::npos) return line;
    return firstLine(log);
}

// A value of a scene file in a few words: "azimuth 160, elevation -160", "[128, 128]".
std::string briefSetting(const nlohmann::ordered_json& value) {
    if (value.is_string()) return value.get<std::string>();
    if (value.is_number()) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", value.get<double>());
        return text;
    }
    std::string out;
    if (value.is_array()) {
        for (const auto& item : value) out += (out.empty() ? "" : ", ") + briefSetting(item);
        return "[" + out + "]";
    }
    if (value.is_object()) {
        for (const auto& [key, item] : value.items()) {
            const std::string text = briefSetting(item);
            out += (out.empty() ? "" : ", ") + key + " " + (item.is_object() ? "(" + text + ")" : text);
        }
        return out;
    }
    return value.dump();
}

// The scene file in one line, in its own order, for the report: "dataset:
// bonsai.nrrd; renderer: mip; camera: azimuth 160, ...". Long values are cut.
std::string sceneSetup(const std::string& path) {
    std::ifstream in(path);
    const auto scene = nlohmann::ordered_json::parse(in, nullptr, false);
    if (!scene.is_object()) return "";
    std::string out;
    for (const auto& [key, value] : scene.items()) {
        std::string text = briefSetting(value);
        if (text.size() > 80) text = text.substr(0, 77) + "...";
        out += (out.empty() ? "" : "; ") + key + ": " + text;
    }
    return out;
}

// The scene file as the report names it: relative to the stages' root
// ("mip/scenes/bonsai_oblique.json"), else its bare name.
std::string sceneFile(const std::string& scenePath, const std::string& root) {
    fs::path base = fs::path(root).lexically_normal();
    if (base.filename().empty()) base = base.parent_path();  // "reference/"
    const fs::path file = fs::path(scenePath).lexically_relative(base);
    return file.empty() || *file.begin() == ".." ? fs::path(scenePath).filename().string() : file.string();
}

// The stubs a scene reached (the worker's "stubs"), and whether they kept
// it from showing the stage's own code: a stub of another stage (a
// prerequisite still the starter code, in a self-check of the student's
// whole tree) blocks the scene, which then counts neither for nor against
// this stage (scoreStage) and gets no hint.
void markStubsReached(json& entry, const std::string& stage, const RunOutcome& outcome, const std::string& scene,
                      double* credit) {
    const auto reached = outcome.results.stubs.find(scene);
    if (reached == outcome.results.stubs.end() || reached->second.empty()) return;
    entry["not_implemented_reached"] = reached->second;
    std::vector<std::string> others;
    for (const std::string& stub : reached->second)
        if (stub.substr(0, stub.find('/')) != stage) others.push_back(stub);
    if (others.empty()) return;
    entry["status"] = "blocked";
    entry["blocked_by"] = others;
    entry["message"] = safeText("blocked by " + stubListText(others) + ", not yet implemented: this scene cannot show " +
                                stage + " until they are (it counts neither for nor against " + stage + ")");
    *credit = 0.0;
}

// One scene's entry: compared with the expected image when the worker sent
// one; the images go into the report folder (written here, by the grader).
json scoreScene(const GradedScene& scene, const StageRun& run, const RunOutcome& outcome, const fs::path& expected,
                const fs::path& report, const std::string& ended, double* credit) {
    json entry = {{"name", scene.name}, {"max_score", 0.0}, {"score", 0.0}, {"tolerance", toJson(scene.tolerance)},
                  {"weight", scene.weight}, {"hidden", scene.hidden}};
    if (!scene.about.empty()) entry["about"] = scene.about;
    const std::string setup = sceneSetup(scene.scenePath);
    if (!setup.empty()) entry["setup"] = setup;
    const fs::path want = expected / (scene.name + ".png");
    const std::string base = run.stage + "/" + scene.name;
    *credit = 0.0;
    try {
        if (!outcome.compiled) throw Error("not rendered: the stage's C++ did not compile");
        if (!fs::exists(want)) throw Error("no expected image " + want.string());
        copyIntoReport(want, report / (scene.name + ".reference.png"));
        entry["images"] = {{"reference", base + ".reference.png"}};
        const auto got = outcome.results.images.find(scene.name);
        const auto error = outcome.results.errors.find("scene:" + scene.name);
        if (got != outcome.results.images.end()) {
            const Image a = loadPng(want.string());
            Image flipMap, differenceMap;
            const ImageMetrics m = compareForGrading(a, got->second, scene.tolerance, &flipMap, &differenceMap);
            savePng(got->second, (report / (scene.name + ".submission.png")).string());
            savePng(flipMap, (report / (scene.name + ".flip.png")).string());
            savePng(differenceMap, (report / (scene.name + ".difference.png")).string());
            entry["images"]["submission"] = base + ".submission.png";
            entry["images"]["flip"] = base + ".flip.png";
            entry["images"]["difference"] = base + ".difference.png";
            entry.update(sceneVerdict(m, scene.tolerance, credit));
        } else if (error != outcome.results.errors.end()) {
            throw Error(firstLine(relativePaths(error->second.value("message", "error"), run, kMaxMessageBytes)));
        } else {
            throw Error(outcome.results.problem.empty() ? "no image: the stage's process " + ended + " before this scene"
                                                        : outcome.results.problem);
        }
    } catch (const std::exception& e) {
        entry["status"] = "error";
        entry["message"] = safeText(e.what());
    }
    markStubsReached(entry, run.stage, outcome, scene.name, credit);
    return entry;
}

json scoreCheck(const GradedCheck& check, const StageRun& run, const RunOutcome& outcome, const fs::path& expected,
                const std::string& ended, double* credit) {
    json entry = {{"name", check.name}, {"weight", check.weight}};
    for (const FunctionCheckInfo& info : functionChecks())
        if (info.name == check.name) entry["description"] = info.description;
    *credit = 0.0;
    try {
        if (!outcome.compiled) throw Error("not run: the stage's C++ did not compile");
        const auto want = readJson(expected / "checks" / (check.name + ".json"));
        if (!want) throw Error("no expected outputs for check " + check.name);
        const auto got = outcome.results.checks.find(check.name);
        const auto error = outcome.results.errors.find("check:" + check.name);
        if (got != outcome.results.checks.end()) {
            const CheckComparison c = compareFunctionCheck(check.name, *want, got->second);
            *credit = c.cases > 0 ? creditForFailedCases(double(c.failed) / c.cases) : 0.0;
            entry["status"] = c.failed == 0 && c.cases > 0 ? "passed" : "failed";
            entry["message"] = c.summary;
            json examples = json::array();  // built from the values the stage returned
            for (const std::string& example : c.examples) examples.push_back(safeText(example));
            entry["examples"] = examples;
            if (!c.inputs.empty()) entry["inputs"] = c.inputs;
        } else if (error != outcome.results.errors.end()) {
            throw Error(firstLine(relativePaths(error->second.value("message", "error"), run, kMaxMessageBytes)));
        } else {
            throw Error(outcome.results.problem.empty() ? "no result: the stage's process " + ended + " before this check"
                                                        : outcome.results.problem);
        }
    } catch (const std::exception& e) {
        entry["status"] = "error";
        entry["message"] = safeText(e.what());
    }
    return entry;
}

// The prerequisites' stubs that blocked scenes, each once.
std::vector<std::string> blockers(const json& scenes) {
    std::vector<std::string> by;
    for (const json& e : scenes)
        for (const json& stub : e.value("blocked_by", json::array()))
            if (stub.is_string() && !std::count(by.begin(), by.end(), stub.get<std::string>())) by.push_back(stub);
    return by;
}

// The stage's status and one-line message.
std::pair<std::string, std::string> stageStatus(const RunOutcome& outcome, const std::string& compileLog,
                                                const json& scenes, const json& checks) {
    bool allPassed = true;
    std::string firstError;
    int failed = 0;
    int blocked = 0;
    for (const json* items : {&scenes, &checks})
        for (const json& e : *items) {
            if (e["status"] == "passed") continue;
            if (e["status"] == "blocked" && ++blocked) continue;
            allPassed = false;
            ++failed;
            if (e["status"] == "error" && firstError.empty()) firstError = e["message"];
        }
    if (!outcome.problem.empty()) return {outcome.problemKind, safeText(outcome.problem)};
    if (!compileLog.empty()) return {"compile_error", errorLine(compileLog)};
    if (!outcome.finished && outcome.ended.rfind("timed out", 0) == 0)
        return {"timeout", "the stage " + outcome.ended + " (an endless loop?); scenes finished before it are scored"};
    if (const auto loop = outcome.results.errors.find("stage:loop"); loop != outcome.results.errors.end())
        return {"timeout", safeText(loop->second.value("message", "a loop ran away"))};  // the worker's runaway-loop check
    if (!outcome.finished && outcome.ended.rfind("crashed", 0) == 0)
        return {"crashed", "the stage's process " + outcome.ended};
    for (const auto& [key, error] : outcome.results.errors)  // a C++ stage's host
        if (error.value("kind", "") == "crashed") return {"crashed", safeText(error.value("message", "crashed"))};
    if (!outcome.stubs.empty()) {
        std::string names;
        for (const std::string& s : outcome.stubs) names += (names.empty() ? "" : ", ") + safeText(s, kMaxNameBytes);
        return {"not_implemented", names + (outcome.stubs.size() == 1 ? " is" : " are") + " not yet implemented"};
    }
    const std::string blockedNote = blocked == 0 ? "" : "; " + std::to_string(blocked) + " blocked by " +
                                                            stubListText(blockers(scenes)) + " (not yet implemented): not graded";
    if (allPassed && blocked > 0)
        return {"blocked", "every item that ran this stage's code is within its tolerance" + blockedNote};
    if (allPassed) return {"passed", "every scene and check within its tolerance"};
    return {firstError.empty() ? "failed" : "error",
            std::to_string(failed) + " of " + std::to_string(scenes.size() + checks.size() - blocked) +
                " items outside tolerance" + blockedNote + (firstError.empty() ? "" : "; " + firstError)};
}

}  // namespace

namespace {

struct Points {
    double points = 0.0, score = 0.0;   // the stage's points that were graded, and its score
    json allPass;                      // the share only a stage with every item passed earns
    std::vector<std::string> failed, blocked;  // sorted: a mistake's signature, and the blocked items
};

// Points per item, in proportion to weight, for all but the share that only
// a stage with every item passed earns (grading.h); sets each item's
// max_score and score. Blocked scenes are not graded: the part of the stage
// that ran its own code is graded as the whole stage would be, for its
// share of the points.
Points awardPoints(double stagePoints, double weightSum, double blockedWeight, double credit, json& scenes, json& checks) {
    Points p;
    const double gradableWeight = weightSum - blockedWeight;
    p.points = weightSum > 0 ? stagePoints * gradableWeight / weightSum : stagePoints;
    const double perWeight = pointsPerWeight(p.points, gradableWeight);
    for (json* items : {&scenes, &checks})
        for (json& e : *items) {
            const bool isBlocked = e["status"] == "blocked";
            e["max_score"] = isBlocked ? 0.0 : perWeight * e["weight"].get<double>();
            e["score"] = e["max_score"].get<double>() * e["credit"].get<double>();
            if (isBlocked) p.blocked.push_back(e["name"]);
            else if (e["status"] != "passed") p.failed.push_back(e["name"]);
        }
    std::sort(p.failed.begin(), p.failed.end());
    const bool allPassed = gradableWeight > 0 && p.failed.empty();
    const double bonusMax = allPassPoints(p.points, gradableWeight);
    p.allPass = {{"max_score", bonusMax},
                 {"score", allPassed ? bonusMax : 0.0},
                 {"status", allPassed ? "passed" : "failed"},
                 {"message", allPassed ? "every scene and check passed" : "earned only when every scene and check passes"}};
    p.score = perWeight * credit + (allPassed ? bonusMax : 0.0);
    return p;
}

}  // namespace

json scoreStage(const StageRun& run, const RunOutcome& outcome, const StageManifest& manifest,
                const GraderOptions& options, const std::string& reportStageDir) {
    json stage = {{"stage", manifest.stage}, {"title", manifest.title}, {"max_score", manifest.points}};
    if (!manifest.about.empty()) stage["about"] = manifest.about;
    const fs::path expected = fs::path(options.expectedDir) / manifest.stage, report = reportStageDir;
    fs::create_directories(report);
    json stubs = json::array();
    for (const std::string& s : outcome.stubs) stubs.push_back(safeText(s, kMaxNameBytes));
    stage["not_implemented"] = stubs;
    std::string compileLog = outcome.compiled ? "" : relativePaths(outcome.compileLog, run);
    for (const auto& [key, error] : outcome.results.errors)
        if (error.value("kind", "") == "compile_error" && compileLog.empty())
            compileLog = relativePaths(error.value("message", ""), run);
    const bool ran = outcome.problem.empty();
    double weightSum = 0.0, blockedWeight = 0.0, credit = 0.0;
    json scenes = json::array(), checks = json::array();
    for (const GradedScene& scene : manifest.scenes) {
        double c = 0.0;
        json entry = scoreScene(scene, run, outcome, expected, report, outcome.ended, &c);
        if (!ran) entry["message"] = safeText(outcome.problem);
        entry["scene_file"] = sceneFile(scene.scenePath, options.referenceRoot);
        weightSum += scene.weight;
        if (entry["status"] == "blocked") blockedWeight += scene.weight;
        credit += scene.weight * c;
        entry["credit"] = c;
        scenes.push_back(entry);
    }
    for (const GradedCheck& check : manifest.checks) {
        double c = 0.0;
        json entry = scoreCheck(check, run, outcome, expected, outcome.ended, &c);
        if (!ran) entry["message"] = safeText(outcome.problem);
        weightSum += check.weight;
        credit += check.weight * c;
        entry["credit"] = c;
        checks.push_back(entry);
    }
    const Points p = awardPoints(manifest.points, weightSum, blockedWeight, credit, scenes, checks);
    stage["scenes"] = scenes;
    stage["checks"] = checks;
    if (!p.blocked.empty()) {
        stage["max_score"] = p.points;
        stage["blocked"] = {{"items", p.blocked}, {"by", blockers(scenes)}, {"points", manifest.points - p.points}};
    }
    stage["all_pass"] = p.allPass;
    stage["score"] = p.score;
    stage["sandbox"] = outcome.sandbox;
    // The worker's last line names the GL it rendered with.
    if (const std::size_t gl = outcome.output.rfind("gl: "); gl != std::string::npos)
        stage["gl"] = safeText(outcome.output.substr(gl + 4, outcome.output.find('\n', gl) - gl - 4), 200);
    if (!compileLog.empty()) stage["log"] = compileLog;
    auto [status, message] = stageStatus(outcome, compileLog, scenes, checks);
    // The worker's output (what a C++ stage printed, a crash) helps when something went wrong.
    bool anyError = false;
    for (const json* items : {&scenes, &checks})
        for (const json& e : *items) anyError = anyError || e["status"] == "error";
    if (ran && (!outcome.finished || anyError) && !outcome.output.empty() && status != "compile_error")
        stage["log"] = relativePaths(outcome.output, run);
    if (manifest.points == 0.0 && status == "passed") status = "example";
    if (status == "failed") {  // a known mistake's signature (grading.h): what it suggests
        const std::vector<std::string> hints = hintsFor(manifest, p.failed, p.blocked);
        if (!hints.empty())
            stage["hints"] = std::vector<std::string>(hints.begin(), hints.begin() + std::min<std::size_t>(3, hints.size()));
    }
    if (!manifest.requires.empty()) stage["requires"] = manifest.requires;
    stage["status"] = status;
    stage["message"] = message;
    return stage;
}

}  // namespace voxlab::grading
