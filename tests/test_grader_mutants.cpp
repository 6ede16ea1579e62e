// The mutant suite (reference/<stage>/mutants.json, tests/mutants/README.md): realistic student bugs,
// each a one-line change to a copy of reference/. The grader must fail
// every one of them in its stage, while the reference passes (test_grader).
// Also the calibration the tolerances rest on: the reference rendered
// another way (hardware instead of explicit trilinear filtering, another
// llvmpipe thread count) passes against itself; and the one the points rest
// on: a mistake at one condition costs less than one seen everywhere.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "support/run_command.h"
#include "voxlab/gl_context.h"
#include "voxlab/grader.h"
#include "voxlab/grading.h"
#include "voxlab/image_metrics.h"
#include "voxlab/image.h"
#include "voxlab/render_engine.h"
#include "voxlab/scene.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSource = VOXLAB_SOURCE_DIR;

GraderOptions gradingOptions(const fs::path& root, const fs::path& reference = kSource / "reference");

// A mutant (a bug) or a correct alternative (about: how the student wrote it).
struct Mutant {
    std::string stage, name, file, find, replace, bug, function, hint;
    bool gross = false;
    std::vector<std::string> conditions;  // wrong only under these (docs/grading.md)
};

// Every stage's reference/<stage>/mutants.json (tests/mutants/README.md), in
// teaching order; a stage's file names only that stage's mutants.
std::vector<Mutant> loadList(const char* key) {
    std::vector<Mutant> mutants;
    for (const StageManifest& stage : stageManifests((kSource / "reference").string())) {
        const fs::path file = kSource / "reference" / stage.stage / "mutants.json";
        if (!fs::exists(file)) continue;
        const json j = json::parse(readFile(file));
        for (const json& m : j.value(key, json::array())) {
            mutants.push_back({m.at("stage"), m.at("name"), m.at("file"), m.at("find"), m.at("replace"),
                               m.value("bug", m.value("about", "")), m.value("function", ""), m.value("hint", ""),
                               m.value("gross", false), m.value("conditions", std::vector<std::string>{})});
            if (mutants.back().stage != stage.stage)
                throw std::runtime_error(file.string() + ": " + mutants.back().name + " is a mutant of another stage");
        }
    }
    return mutants;
}

std::vector<Mutant> loadMutants() { return loadList("mutants"); }
std::vector<Mutant> loadAlternatives() { return loadList("alternatives"); }

// Each mutant or alternative applied to a copy of its stage's folder, all
// graded in one grading run.
std::vector<json> gradeVariants(const std::vector<Mutant>& variants, const fs::path& root,
                                const fs::path& reference = kSource / "reference") {
    std::vector<Submission> submissions;
    for (const Mutant& m : variants) {
        const fs::path folder = root / "submissions" / m.name;
        // Only the stage's folder: grading takes every other stage from the reference.
        fs::create_directories(folder);
        fs::copy(reference / m.stage, folder / m.stage, fs::copy_options::recursive);
        std::string text = readFile(folder / m.file);
        const std::size_t at = text.find(m.find);
        if (at == std::string::npos) throw std::runtime_error(m.name + ": the find text is not in " + m.file);
        text.replace(at, m.find.size(), m.replace);
        std::ofstream(folder / m.file) << text;
        submissions.push_back({m.name, folder.string(), (root / "reports" / m.name).string(), {m.stage}});
    }
    return gradeSubmissions(submissions, gradingOptions(root, reference));
}

// The names of a stage's items that did not pass: the mutant's signature.
std::vector<std::string> failedItems(const json& stage) {
    std::vector<std::string> names;
    for (const char* kind : {"scenes", "checks"})
        for (const json& item : stage.value(kind, json::array()))
            if (item.value("status", "") != "passed") names.push_back(item.value("name", ""));
    std::sort(names.begin(), names.end());
    return names;
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / ("voxlab_mutants_" + std::to_string(getpid())) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Grading against the reference, expected outputs rendered into ROOT/expected
// with one llvmpipe thread, two stages at once.
GraderOptions gradingOptions(const fs::path& root, const fs::path& reference) {
    GraderOptions o;
    o.voxlab = VOXLAB_BINARY;
    o.referenceRoot = reference.string();
    o.expectedDir = (root / "expected").string();
    o.jobs = 2;
    o.renderThreads = 1;
    o.progress = false;
    return o;
}

// Each mutant and each alternative applies cleanly inside a solution block;
// every graded function has at least 5 mutants, 120 in all; a hint names
// the misconception ("Looks like ...") and holds no line of the solution.
// A mutant is a bug, not a broken build: its items fail, or a scene stops
// with a one-line error naming what the stage returned (a shear-warp
// factorisation whose intermediate image cannot exist); never a compile
// error, a crash or a timeout (statuses of their own).
bool failsAsABug(const json& stage) { return stage["status"] == "failed" || stage["status"] == "error"; }

TEST(MutantSuite, EveryGradedFunctionHasFiveMutantsThatApplyCleanly) {
    std::map<std::string, int> perFunction;
    const std::vector<Mutant> mutants = loadMutants(), alternatives = loadAlternatives();
    std::vector<Mutant> all = mutants;
    all.insert(all.end(), alternatives.begin(), alternatives.end());
    for (const Mutant& m : all) {
        EXPECT_EQ(m.file.rfind(m.stage + "/", 0), 0u) << m.name << ": the file must be in its stage's folder";
        const std::string text = readFile(kSource / "reference" / m.file);
        const std::size_t at = text.find(m.find);
        ASSERT_NE(at, std::string::npos) << m.name << ": '" << m.find << "' is not in reference/" << m.file;
        EXPECT_EQ(text.find(m.find, at + 1), std::string::npos) << m.name << ": '" << m.find << "' occurs twice";
        // Inside the solution: after a BEGIN SOLUTION with no END between.
        const std::size_t begin = text.rfind("BEGIN SOLUTION", at), end = text.rfind("END SOLUTION", at);
        EXPECT_TRUE(begin != std::string::npos && (end == std::string::npos || end < begin))
            << m.name << ": the change is outside the solution block";
        EXPECT_NE(m.find, m.replace) << m.name;
        const StageManifest manifest = loadStageManifest((kSource / "reference").string(), m.stage);
        EXPECT_NE(std::find(manifest.functions.begin(), manifest.functions.end(), m.function), manifest.functions.end())
            << m.name << ": '" << m.function << "' is not one of " << m.stage << "'s functions";
    }
    for (const Mutant& m : mutants) {
        ++perFunction[m.stage + "/" + m.function];
        EXPECT_EQ(m.hint.rfind("Looks like", 0), 0u) << m.name << ": a hint starts \"Looks like\"";
        // No solution line (of some length) appears in the hint.
        std::istringstream solution(readFile(kSource / "reference" / m.file));
        for (std::string line; std::getline(solution, line);) {
            line.erase(0, line.find_first_not_of(" \t"));
            if (line.size() >= 16 && line.rfind("//", 0) != 0)
                EXPECT_EQ(m.hint.find(line), std::string::npos) << m.name << ": the hint holds solution code";
        }
    }
    EXPECT_GE(mutants.size(), 120u);
    for (const std::string& stage : gradedStages((kSource / "reference").string())) {
        const StageManifest manifest = loadStageManifest((kSource / "reference").string(), stage);
        for (const std::string& f : manifest.functions)
            EXPECT_GE(perFunction[stage + "/" + f], 5) << stage << "/" << f << " needs at least five mutants";
    }
}

// Every mutant, graded in its own stage in one grading run: it fails its
// stage and costs at least 2 of 10 points; a gross one (the stage broken
// beyond use) keeps at most 2 of 10. Each mutant's signature (the items it
// fails) is written to VOXLAB_MUTANT_SIGNATURES when that is set, for
// tools/mutant_hints.py; a hint the manifests hold for the signature must
// reach the report.
TEST(MutantSuite, TheGraderFailsEveryMutant) {
    const std::vector<Mutant> mutants = loadMutants();
    const fs::path root = scratch("suite");
    const std::vector<json> reports = gradeVariants(mutants, root);
    ASSERT_EQ(reports.size(), mutants.size());
    json signatures = json::array();
    for (std::size_t i = 0; i < mutants.size(); ++i) {
        const Mutant& m = mutants[i];
        const json& stage = reports[i]["stages"].at(0);
        EXPECT_EQ(stage["stage"], m.stage);
        const double score = stage["score"].get<double>(), max = stage["max_score"].get<double>();
        EXPECT_NE(stage["status"], "passed") << m.name << " (" << m.bug << ") passed " << m.stage;
        EXPECT_TRUE(failsAsABug(stage)) << m.name << ": " << stage["status"] << ": " << stage["message"];
        EXPECT_LE(score, max - 0.2 * max + 1e-9) << m.name << " lost less than 2 of 10 points";
        if (m.gross) EXPECT_LE(score, 0.2 * max + 1e-9) << m.name << " is gross but kept more than 2 of 10";
        signatures.push_back({{"stage", m.stage}, {"mutant", m.name}, {"failed", failedItems(stage)}});
        std::string hints;
        for (const json& h : stage.value("hints", json::array())) hints += h.get<std::string>() + " | ";
        std::printf("%-14s %-40s %-6s %5.2f/%g %s  %s\n", m.stage.c_str(), m.name.c_str(), m.gross ? "gross" : "",
                    score, max, stage["message"].get<std::string>().c_str(), hints.c_str());
        // The report shows the manifest's hints for this signature (up to
        // three); the mutant's own is among them.
        const std::vector<std::string> known = hintsFor(
            loadStageManifest((kSource / "reference").string(), m.stage), failedItems(stage));
        if (!m.hint.empty() && !known.empty()) {
            EXPECT_NE(std::find(known.begin(), known.end(), m.hint), known.end())
                << m.name << ": the manifest's hints for its signature do not include its own; run "
                   "tools/mutant_hints.py (docs/grading.md)";
            EXPECT_EQ(stage.value("hints", json::array()).size(), std::min<std::size_t>(3, known.size())) << m.name;
            EXPECT_NE(hints.find(known.front()), std::string::npos) << m.name;
        }
    }
    if (const char* out = std::getenv("VOXLAB_MUTANT_SIGNATURES"))
        std::ofstream(out) << json{{"signatures", signatures}}.dump(1) << "\n";
    fs::remove_all(root);
}

// Correct solutions written the ways students write them keep full marks.
TEST(MutantSuite, EveryCorrectAlternativeKeepsFullMarks) {
    const std::vector<Mutant> alternatives = loadAlternatives();
    ASSERT_GE(alternatives.size(), 20u) << "the stages' mutants.json need their correct alternatives";
    const fs::path root = scratch("alternatives");
    const std::vector<json> reports = gradeVariants(alternatives, root);
    ASSERT_EQ(reports.size(), alternatives.size());
    for (std::size_t i = 0; i < alternatives.size(); ++i) {
        const json& stage = reports[i]["stages"].at(0);
        EXPECT_EQ(stage["status"], "passed") << alternatives[i].name << " (" << alternatives[i].bug
                                             << "): " << stage["message"];
        EXPECT_DOUBLE_EQ(stage["score"].get<double>(), stage["max_score"].get<double>()) << alternatives[i].name;
    }
    fs::remove_all(root);
}

// The other filtering: every grading scene that filters in hardware is
// graded with explicit trilinear interpolation instead (a copy of
// reference/ with its scene files changed; the sampling stage's scenes,
// which test explicit trilinear and nearest on purpose, stay as they are).
// Every mutant still fails and loses at least 2 of 10, every alternative
// keeps 10/10. Heavy (tests/CMakeLists.txt): another full suite.
TEST(MutantSuite, TheOtherFilteringStillFailsEveryMutantAndPassesEveryAlternative) {
    const fs::path root = scratch("other_filtering"), reference = root / "reference";
    fs::copy(kSource / "reference", reference, fs::copy_options::recursive);
    int flipped = 0;
    for (const auto& entry : fs::recursive_directory_iterator(reference)) {
        if (entry.path().extension() != ".json" || entry.path().parent_path().filename() != "scenes") continue;
        std::string text = readFile(entry.path());
        const std::string hardware = "\"interpolation\": \"hardware\"";
        const std::size_t at = text.find(hardware);
        if (at == std::string::npos) continue;
        text.replace(at, hardware.size(), "\"interpolation\": \"trilinear\"");
        std::ofstream(entry.path()) << text;
        ++flipped;
    }
    EXPECT_GE(flipped, 40);
    const std::vector<Mutant> mutants = loadMutants(), alternatives = loadAlternatives();
    const std::vector<json> bugs = gradeVariants(mutants, root / "mutants", reference);
    for (std::size_t i = 0; i < mutants.size(); ++i) {
        const json& stage = bugs[i]["stages"].at(0);
        EXPECT_TRUE(failsAsABug(stage)) << mutants[i].name << ": " << stage["status"] << ": " << stage["message"];
        EXPECT_LE(stage["score"].get<double>(), 0.8 * stage["max_score"].get<double>() + 1e-9) << mutants[i].name;
        if (mutants[i].gross) EXPECT_LE(stage["score"].get<double>(), 0.2 * stage["max_score"].get<double>() + 1e-9);
    }
    const std::vector<json> fine = gradeVariants(alternatives, root / "alternatives", reference);
    for (std::size_t i = 0; i < alternatives.size(); ++i) {
        const json& stage = fine[i]["stages"].at(0);
        EXPECT_EQ(stage["status"], "passed") << alternatives[i].name << ": " << stage["message"];
    }
    std::printf("%d scenes graded with explicit trilinear filtering: %zu mutants, %zu alternatives\n", flipped,
                mutants.size(), alternatives.size());
    fs::remove_all(root);
}

// Points follow severity on the project's own mutants: in every stage that
// has mutants wrong at one condition only (mutants.json "conditions": a
// step other than 1, exact zeros, a white background, ...), each of them
// keeps more points than every mutant of the stage visible on at least 40%
// of the pixels of the stage's scenes (weighted as the scenes are), and
// loses at least 2 of 10. A condition's scenes are there to catch its
// mistakes, not to make them cost as much as a broken stage. Heavy: grades
// every mutant of those stages.
double pixelsOff(const json& stage) {
    double off = 0.0, weights = 0.0;
    for (const json& scene : stage.value("scenes", json::array())) {
        const double w = scene.value("weight", 1.0);
        off += w * scene.value("metrics", json::object()).value("fraction_over", 0.0);
        weights += w;
    }
    return weights > 0 ? off / weights : 0.0;
}

TEST(GradingCalibration, AMistakeAtOneConditionCostsLessThanOneSeenEverywhere) {
    std::set<std::string> stages;
    for (const Mutant& m : loadMutants())
        if (!m.conditions.empty()) stages.insert(m.stage);
    std::vector<Mutant> mutants;
    for (const Mutant& m : loadMutants())
        if (stages.count(m.stage)) mutants.push_back(m);
    const fs::path root = scratch("severity");
    const std::vector<json> reports = gradeVariants(mutants, root);
    ASSERT_EQ(reports.size(), mutants.size());
    std::map<std::string, double> narrowest, broadest;  // per stage: the least a one-condition mutant keeps,
                                                        // the most one seen on >= 40% keeps
    for (std::size_t i = 0; i < mutants.size(); ++i) {
        const json& stage = reports[i]["stages"].at(0);
        const double score = 10.0 * stage["score"].get<double>() / stage["max_score"].get<double>();
        const double off = pixelsOff(stage);
        const Mutant& m = mutants[i];
        std::printf("%-14s %-36s %5.1f%% of pixels %2zu items failed %5.2f/10 %s\n", m.stage.c_str(), m.name.c_str(),
                    100.0 * off, failedItems(stage).size(), score, m.conditions.empty() ? "" : "one condition");
        if (!m.conditions.empty()) {
            narrowest[m.stage] = narrowest.count(m.stage) ? std::min(narrowest[m.stage], score) : score;
            EXPECT_LE(score, 8.0 + 1e-9) << m.name;
        }
        if (off >= 0.4) broadest[m.stage] = broadest.count(m.stage) ? std::max(broadest[m.stage], score) : score;
    }
    for (const auto& [stage, least] : narrowest) {
        if (!broadest.count(stage)) continue;
        std::printf("%-14s one condition keeps >= %.2f, seen on >= 40%% of pixels keeps <= %.2f\n", stage.c_str(),
                    least, broadest[stage]);
        EXPECT_LT(broadest[stage], least) << stage;
    }
    EXPECT_GE(narrowest.size(), 5u);
    fs::remove_all(root);
}

// The reference's own images, with the interpolation switched between the
// explicit trilinear stage and the GPU's filtering, stay within every
// scene's tolerance of the expected images (rendered the usual way by the
// grader, with one llvmpipe thread: this process uses the test's two).
TEST(GradingCalibration, TheReferenceRenderedAnotherWayPasses) {
    const fs::path root = scratch("calibration");
    const GraderOptions o = gradingOptions(root);
    renderExpectedOutputs(o);

    auto context = createHeadlessContext();
    RenderEngine engine(rendererRegistry());
    std::map<std::string, Volume> volumes;
    double worst = 0.0;
    std::string worstScene;
    int worstCluster = 0;
    const std::vector<int> kClusterLevels = {4, 8, 16, 24, 32, 48};
    std::vector<int> clusterAt(kClusterLevels.size(), 0);
    std::string worstClusterScene;
    for (const std::string& stage : gradedStages(o.referenceRoot)) {
        for (const GradedScene& graded : loadStageManifest(o.referenceRoot, stage).scenes) {
            for (int variant = 0; variant < 2; ++variant) {
                Scene scene = Scene::load(graded.scenePath);
                if (variant == 1) {
                    // No other path for nearest, nor for the cubic kernels (the stage itself).
                    if (scene.interpolation == Interpolation::Nearest || isCubic(scene.interpolation)) continue;
                    scene.interpolation = scene.interpolation == Interpolation::Hardware ? Interpolation::Trilinear
                                                                                        : Interpolation::Hardware;
                }
                auto found = volumes.find(scene.dataset);
                if (found == volumes.end()) found = volumes.emplace(scene.dataset, loadVolume(scene.dataset)).first;
                engine.setVolume(found->second);
                const fs::path png = root / (stage + "_" + graded.name + ".png");
                savePng(engine.render(scene), png.string());
                const ImageMetrics m = compareForGrading(loadPng((fs::path(o.expectedDir) / stage /
                                                                  (graded.name + ".png")).string()),
                                                         loadPng(png.string()), graded.tolerance);
                const double ratio = toleranceRatio(m, graded.tolerance);
                EXPECT_LE(ratio, 1.0) << stage << "/" << graded.name << (variant ? " (other filtering)" : "")
                                      << ": fraction over " << m.fractionOver << ", SSIM " << m.ssim << ", FLIP "
                                      << m.flipMean;
                if (ratio > worst) worst = ratio, worstScene = stage + "/" + graded.name + (variant ? "*" : "");
                // The cluster bound's calibration: the largest group at several levels.
                const Image want = loadPng((fs::path(o.expectedDir) / stage / (graded.name + ".png")).string());
                const Image got = loadPng(png.string());
                for (std::size_t k = 0; k < kClusterLevels.size(); ++k)
                    clusterAt[k] = std::max(clusterAt[k], largestCluster(want, got, (kClusterLevels[k] + 0.5) / 255.0));
                if (m.largestCluster > worstCluster)
                    worstCluster = m.largestCluster,
                    worstClusterScene = stage + "/" + graded.name + (variant ? "*" : "");
            }
        }
    }
    std::printf("worst tolerance ratio of the reference against itself: %.3f (%s; * = other filtering)\n", worst,
                worstScene.c_str());
    std::printf("largest cluster of pixels off by more than the cluster bound: %d px (%s)\n", worstCluster,
                worstClusterScene.c_str());
    for (std::size_t k = 0; k < kClusterLevels.size(); ++k)
        std::printf("  largest group off by more than %2d levels: %d px\n", kClusterLevels[k], clusterAt[k]);
    fs::remove_all(root);
}

}  // namespace
}  // namespace voxlab::testing
