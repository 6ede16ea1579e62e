// voxlab grader: scoring one stage's outputs against the expected ones.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "stage_job.h"
#include "voxlab/error.h"
#include "voxlab/function_checks.h"
#include "voxlab/image.h"
#include "voxlab/scene.h"

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
// the project ("shaders/voxlab/ray.glsl").
std::string relativePaths(std::string text, const StageRun& run) {
    replaceAll(text, (fs::path(run.workDir) / "impl").string() + "/", "");
    replaceAll(text, fs::path(run.implementationRoot).lexically_normal().string() + "/", "");
    replaceAll(text, fs::path(projectRoot()).lexically_normal().string() + "/", "");
    return text;
}

std::string firstLine(const std::string& s) { return s.substr(0, s.find('\n')); }

// The line of a compiler log that says what is wrong: the first with
// "error", else the first.
std::string errorLine(const std::string& log) {
    std::istringstream in(log);
    for (std::string line; std::getline(in, line);)
        if (line.find("error") != std::string::npos) return line;
    return firstLine(log);
}

}  // namespace

json scoreStage(const StageRun& run, const RunOutcome& outcome, const StageManifest& manifest,
                const GraderOptions& options, const std::string& submissionFolder) {
    json stage = {{"stage", manifest.stage}, {"title", manifest.title}, {"max_score", manifest.points}};
    const fs::path expected = fs::path(options.expectedDir) / manifest.stage;
    const fs::path output = run.outputDir;
    const std::vector<std::string> stubs = unimplementedFunctions((fs::path(submissionFolder) / manifest.stage).string());
    stage["not_implemented"] = stubs;

    double weightSum = 0.0, credit = 0.0;
    bool allPassed = true;
    std::string compileLog = outcome.compiled ? "" : relativePaths(outcome.compileLog, run);
    std::string firstError;
    json scenes = json::array(), checks = json::array();
    for (const GradedScene& scene : manifest.scenes) {
        weightSum += scene.weight;
        json entry = {{"name", scene.name}, {"max_score", 0.0}, {"score", 0.0}, {"tolerance", toJson(scene.tolerance)}};
        entry["weight"] = scene.weight;
        const fs::path want = expected / (scene.name + ".png");
        const fs::path got = output / (scene.name + run.suffix + ".png");
        const fs::path error = output / (scene.name + run.suffix + ".error.json");
        double sceneCredit = 0.0;
        try {
            if (!outcome.compiled) throw Error("not rendered: the stage's C++ did not compile");
            if (!fs::exists(want)) throw Error("no expected image " + want.string());
            if (fs::exists(got)) {
                const Image a = loadPng(want.string()), b = loadPng(got.string());
                Image flipMap, differenceMap;
                const ImageMetrics m = compareForGrading(a, b, scene.tolerance, &flipMap, &differenceMap);
                const std::string base = manifest.stage + "/" + scene.name;
                fs::copy_file(want, output / (scene.name + ".reference.png"), fs::copy_options::overwrite_existing);
                savePng(flipMap, (output / (scene.name + ".flip.png")).string());
                savePng(differenceMap, (output / (scene.name + ".difference.png")).string());
                entry["images"] = {{"reference", base + ".reference.png"},
                                   {"submission", base + run.suffix + ".png"},
                                   {"flip", base + ".flip.png"},
                                   {"difference", base + ".difference.png"}};
                entry["metrics"] = toJson(m);
                const double ratio = toleranceRatio(m, scene.tolerance);
                sceneCredit = creditForRatio(ratio);
                entry["status"] = ratio <= 1.0 ? "passed" : "failed";
                char line[200];
                std::snprintf(line, sizeof line, "%.2f%% of pixels off by more than %g levels, SSIM %.4f, FLIP %.4f",
                              100.0 * m.fractionOver, scene.tolerance.maxDifference, m.ssim, m.flipMean);
                entry["message"] = line;
            } else if (auto e = readJson(error)) {
                const std::string message = relativePaths(e->value("message", "error"), run);
                if (e->value("kind", "") == "compile_error" && compileLog.empty()) compileLog = message;
                throw Error(firstLine(message));
            } else {
                throw Error("no image: the stage's process " + outcome.ended + " before this scene");
            }
        } catch (const std::exception& e) {
            entry["status"] = "error";
            entry["message"] = e.what();
            if (firstError.empty()) firstError = e.what();
            if (fs::exists(want)) {
                fs::copy_file(want, output / (scene.name + ".reference.png"), fs::copy_options::overwrite_existing);
                entry["images"] = {{"reference", manifest.stage + "/" + scene.name + ".reference.png"}};
            }
        }
        if (entry["status"] != "passed") allPassed = false;
        credit += scene.weight * sceneCredit;
        entry["credit"] = sceneCredit;
        scenes.push_back(entry);
    }
    for (const GradedCheck& check : manifest.checks) {
        weightSum += check.weight;
        json entry = {{"name", check.name}, {"weight", check.weight}};
        for (const FunctionCheckInfo& info : functionChecks())
            if (info.name == check.name) entry["description"] = info.description;
        double checkCredit = 0.0;
        try {
            if (!outcome.compiled) throw Error("not run: the stage's C++ did not compile");
            const auto want = readJson(expected / "checks" / (check.name + ".json"));
            if (!want) throw Error("no expected outputs for check " + check.name);
            const auto got = readJson(output / "checks" / (check.name + run.suffix + ".json"));
            if (got) {
                const CheckComparison c = compareFunctionCheck(check.name, *want, *got);
                checkCredit = c.cases > 0 ? creditForFailedCases(double(c.failed) / c.cases) : 0.0;
                entry["status"] = c.failed == 0 && c.cases > 0 ? "passed" : "failed";
                entry["message"] = c.summary;
                entry["examples"] = c.examples;
            } else if (auto e = readJson(output / "checks" / (check.name + run.suffix + ".error.json"))) {
                throw Error(firstLine(relativePaths(e->value("message", "error"), run)));
            } else {
                throw Error("no result: the stage's process " + outcome.ended + " before this check");
            }
        } catch (const std::exception& e) {
            entry["status"] = "error";
            entry["message"] = e.what();
            if (firstError.empty()) firstError = e.what();
        }
        if (entry["status"] != "passed") allPassed = false;
        credit += check.weight * checkCredit;
        entry["credit"] = checkCredit;
        checks.push_back(entry);
    }
    // Points per item, in proportion to weight.
    const double perWeight = weightSum > 0 ? manifest.points / weightSum : 0.0;
    for (json& e : scenes) {
        e["max_score"] = perWeight * e["weight"].get<double>();
        e["score"] = e["max_score"].get<double>() * e["credit"].get<double>();
    }
    for (json& e : checks) {
        e["max_score"] = perWeight * e["weight"].get<double>();
        e["score"] = e["max_score"].get<double>() * e["credit"].get<double>();
    }
    stage["scenes"] = scenes;
    stage["checks"] = checks;
    stage["score"] = perWeight * credit;
    if (!compileLog.empty()) stage["log"] = compileLog;

    std::string status, message;
    if (!compileLog.empty()) {
        status = "compile_error";
        message = errorLine(compileLog);
    } else if (!outcome.finished && outcome.ended.rfind("timed out", 0) == 0) {
        status = "timeout";
        message = "the stage " + outcome.ended + " (an endless loop?); scenes finished before it are scored";
    } else if (!outcome.finished && outcome.ended.rfind("crashed", 0) == 0) {
        status = "crashed";
        message = "the stage's process " + outcome.ended;
    } else if (!stubs.empty()) {
        status = "not_implemented";
        std::string names;
        for (const std::string& s : stubs) names += (names.empty() ? "" : ", ") + s;
        message = names + (stubs.size() == 1 ? " is" : " are") + " not yet implemented";
    } else if (allPassed) {
        status = "passed";
        message = "every scene and check within its tolerance";
    } else {
        status = firstError.empty() ? "failed" : "error";
        int failed = 0;
        for (const json& e : scenes) failed += e["status"] != "passed";
        for (const json& e : checks) failed += e["status"] != "passed";
        message = std::to_string(failed) + " of " + std::to_string(scenes.size() + checks.size()) +
                  " items outside tolerance" + (firstError.empty() ? "" : "; " + firstError);
    }
    if (!outcome.finished && !outcome.output.empty() && status != "compile_error")
        stage["log"] = relativePaths(outcome.output, run);
    if (manifest.points == 0.0 && status == "passed") status = "example";
    stage["status"] = status;
    stage["message"] = message;
    return stage;
}

}  // namespace voxlab::grading
