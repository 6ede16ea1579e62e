// voxlab: one stage checked in this process (see self_check.h).
#include "voxlab/self_check.h"

#include <filesystem>
#include <map>

#include "voxlab/error.h"
#include "voxlab/grading.h"
#include "voxlab/image.h"
#include "voxlab/render_engine.h"
#include "voxlab/scene.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume.h"

namespace voxlab {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// One scene rendered as the grader's worker renders it (every sample, no
// skipping) and compared as the grader compares it: through 8-bit RGB, the
// form the worker sends its images in.
json checkScene(const GradedScene& graded, RenderEngine& engine, std::map<std::string, Volume>& volumes,
                const fs::path& expected, const fs::path& out, double* credit) {
    json entry = {{"name", graded.name}, {"weight", graded.weight}};
    *credit = 0.0;
    try {
        const Scene scene = gradingSceneFor(graded, volumes, engine);
        const fs::path submission = out / (graded.name + ".submission.png");
        savePng(engine.render(scene), submission.string());
        const fs::path want = expected / (graded.name + ".png");
        if (!fs::exists(want)) throw Error("no expected image " + want.string());
        Image flip, difference;
        const ImageMetrics m =
            compareForGrading(loadPng(want.string()), loadPng(submission.string()), graded.tolerance, &flip, &difference);
        savePng(flip, (out / (graded.name + ".flip.png")).string());
        savePng(difference, (out / (graded.name + ".difference.png")).string());
        entry.update(sceneVerdict(m, graded.tolerance, credit));
        entry["images"] = {{"expected", want.string()}, {"submission", submission.string()},
                           {"flip", (out / (graded.name + ".flip.png")).string()},
                           {"difference", (out / (graded.name + ".difference.png")).string()}};
    } catch (const std::exception& e) {
        entry["status"] = "error";
        entry["message"] = e.what();
    }
    return entry;
}

}  // namespace

json selfCheckStage(const std::string& stage, const SelfCheckOptions& options) {
    const StageManifest manifest = loadStageManifest(options.tree, stage);
    const fs::path out = options.outDir;
    fs::create_directories(out);
    RenderEngine engine(rendererRegistry(), options.tree);
    std::map<std::string, Volume> volumes;  // outlives nothing but the engine's use of it below
    json scenes = json::array();
    double weightSum = 0.0, credit = 0.0;
    bool allPassed = true;
    for (const GradedScene& graded : manifest.scenes) {
        if (graded.hidden) continue;
        double c = 0.0;
        json entry = checkScene(graded, engine, volumes, fs::path(options.expectedDir) / stage, out, &c);
        entry["credit"] = c;
        weightSum += graded.weight;
        credit += graded.weight * c;
        allPassed = allPassed && entry["status"] == "passed";
        scenes.push_back(entry);
    }
    // The grader's arithmetic (grading.h), over these scenes alone.
    return {{"stage", stage},
            {"title", manifest.title},
            {"scenes", scenes},
            {"checks_native_only", manifest.checks.size()},
            {"score", pointsPerWeight(manifest.points, weightSum) * credit +
                          (allPassed ? allPassPoints(manifest.points, weightSum) : 0.0)},
            {"max_score", manifest.points},
            {"status", weightSum == 0 ? "no scenes" : allPassed ? "passed" : "failed"}};
}

}  // namespace voxlab
