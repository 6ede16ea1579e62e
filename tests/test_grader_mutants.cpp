// The mutant suite (tests/mutants/mutants.json): realistic student bugs,
// each a one-line change to a copy of reference/. The grader must fail
// every one of them in its stage, while the reference passes (test_grader).
// Also the calibration the tolerances rest on: the reference rendered
// another way (hardware instead of explicit trilinear filtering, another
// llvmpipe thread count) passes against itself.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "support/run_command.h"
#include "voxlab/gl_context.h"
#include "voxlab/grader.h"
#include "voxlab/grading.h"
#include "voxlab/image_metrics.h"
#include "voxlab/image.h"
#include "voxlab/render_engine.h"
#include "voxlab/scene.h"
#include "voxlab/volume.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSource = VOXLAB_SOURCE_DIR;

struct Mutant {
    std::string stage, name, file, find, replace, bug;
};

std::vector<Mutant> loadMutants() {
    const json j = json::parse(readFile(kSource / "tests/mutants/mutants.json"));
    std::vector<Mutant> mutants;
    for (const json& m : j.at("mutants"))
        mutants.push_back({m.at("stage"), m.at("name"), m.at("file"), m.at("find"), m.at("replace"), m.at("bug")});
    return mutants;
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / ("voxlab_mutants_" + std::to_string(getpid())) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Grading against the reference, expected outputs rendered into ROOT/expected
// with one llvmpipe thread, two stages at once.
GraderOptions gradingOptions(const fs::path& root) {
    GraderOptions o;
    o.voxlab = VOXLAB_BINARY;
    o.referenceRoot = (kSource / "reference").string();
    o.expectedDir = (root / "expected").string();
    o.jobs = 2;
    o.renderThreads = 1;
    o.progress = false;
    return o;
}

TEST(MutantSuite, EveryGradedStageHasAtLeastThreeMutantsThatApplyCleanly) {
    std::map<std::string, int> perStage;
    for (const Mutant& m : loadMutants()) {
        ++perStage[m.stage];
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
    }
    for (const std::string& stage : gradedStages((kSource / "reference").string())) {
        if (loadStageManifest((kSource / "reference").string(), stage).points == 0.0) continue;  // worked example
        EXPECT_GE(perStage[stage], 3) << "stage " << stage << " needs at least three mutants";
    }
}

// Every mutant, graded in its own stage in one grading run.
TEST(MutantSuite, TheGraderFailsEveryMutant) {
    const std::vector<Mutant> mutants = loadMutants();
    const fs::path root = scratch("suite");
    std::vector<Submission> submissions;
    for (const Mutant& m : mutants) {
        const fs::path folder = root / "submissions" / m.name;
        // Only the stage's folder: grading takes every other stage from the reference.
        fs::create_directories(folder);
        fs::copy(kSource / "reference" / m.stage, folder / m.stage, fs::copy_options::recursive);
        std::string text = readFile(folder / m.file);
        const std::size_t at = text.find(m.find);
        ASSERT_NE(at, std::string::npos) << m.name;
        text.replace(at, m.find.size(), m.replace);
        std::ofstream(folder / m.file) << text;
        submissions.push_back({m.name, folder.string(), (root / "reports" / m.name).string(), {m.stage}});
    }
    const GraderOptions o = gradingOptions(root);
    const std::vector<json> reports = gradeSubmissions(submissions, o);
    ASSERT_EQ(reports.size(), mutants.size());
    for (std::size_t i = 0; i < mutants.size(); ++i) {
        const json& stage = reports[i]["stages"].at(0);
        EXPECT_EQ(stage["stage"], mutants[i].stage);
        EXPECT_NE(stage["status"], "passed") << mutants[i].name << " (" << mutants[i].bug << ") passed "
                                             << mutants[i].stage;
        EXPECT_LT(stage["score"].get<double>(), stage["max_score"].get<double>()) << mutants[i].name;
        // A mutant is a bug, not a broken build.
        EXPECT_TRUE(stage["status"] == "failed") << mutants[i].name << ": " << stage["status"] << ": "
                                                 << stage["message"];
        std::printf("%-14s %-36s %-8s %5.2f/%g  %s\n", mutants[i].stage.c_str(), mutants[i].name.c_str(),
                    stage["status"].get<std::string>().c_str(), stage["score"].get<double>(),
                    stage["max_score"].get<double>(), stage["message"].get<std::string>().c_str());
    }
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
    RenderEngine engine;
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
                    if (scene.interpolation == Interpolation::Nearest) continue;  // no other path for nearest
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
