// voxlab grade-worker: the child process that runs one stage of one
// implementation for the grader (grader.h). Not meant to be run by hand.
//
// It renders each of the stage's grading scenes and runs each function
// check, and sends every result, or the error that stopped it, through the
// results channel (fd 3, voxlab/worker_results.h). It writes no files: the
// grader starts it in a sandbox where it cannot (child_process.h). Work
// that hangs or crashes is the parent's to notice.
#include <fcntl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "voxlab/error.h"
#include "voxlab/function_checks.h"
#include "voxlab/gl_context.h"
#include "voxlab/grading.h"
#include "voxlab/image.h"
#include "voxlab/ray_profile.h"
#include "voxlab/render_engine.h"
#include "voxlab/shader.h"
#include "voxlab/stage_host.h"
#include "voxlab/stage_library.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume.h"
#include "voxlab/worker_results.h"

namespace voxlab::cli {

namespace {

std::string errorKind(const std::exception& e) {
    if (dynamic_cast<const ShaderError*>(&e)) return "compile_error";
    if (dynamic_cast<const NotImplemented*>(&e)) return "not_implemented";
    if (dynamic_cast<const StageCrashed*>(&e)) return "crashed";
    return "error";
}

// An endless loop does not hang llvmpipe: Mesa's gallivm ends every shader
// loop after 65 535 rounds, so a loop whose counter never reaches its bound
// (m += 0) returns wrong pixels in seconds instead of running into the time
// limit. Counting the samples of a scene that rays sample tells the two
// apart: a stage's loop takes about the sampling rule's number (a few times
// that at most, if it reads a sample twice), a runaway loop hundreds of
// times more. It is reported as the time-out it would be on a GPU.
//
// The count is taken first, before any scene renders, on the first
// countable scene shrunk to at most kLoopCheckSide pixels a side: its budget
// is a number of samples per pixel, never a time, so a loaded machine
// decides the same, and a runaway loop costs 65 535 rounds for a few
// thousand pixels instead of every grading scene's (which on a busy machine
// ran into the stage's time limit). Returns the message, or "" for none.
constexpr int kLoopCheckSide = 48;

std::string runawayLoop(const StageManifest& manifest, std::map<std::string, Volume>& volumes, RenderEngine& engine) {
    for (const GradedScene& graded : manifest.scenes) {
        try {
            Scene scene = gradingSceneFor(graded, volumes, engine);
            if (!samplesCountable(rendererRegistry(), scene)) continue;
            const double shrink = std::min(1.0, double(kLoopCheckSide) / std::max(scene.width, scene.height));
            scene.width = std::max(1, int(std::lround(scene.width * shrink)));
            scene.height = std::max(1, int(std::lround(scene.height * shrink)));
            const double rule = samplesByRule(*engine.volume(), scene);
            const double taken = engine.countSamples(scene);
            const double pixels = double(scene.width) * double(scene.height);
            if (taken <= 8.0 * rule + 16.0 * pixels) return "";
            char message[400];
            std::snprintf(message, sizeof message,
                          "a loop ran away: scene %s took %.3g samples at %dx%d where the sampling rule gives %.3g "
                          "(llvmpipe ends any loop after 65535 rounds; a GPU would hang): does a loop's "
                          "counter never reach its bound?",
                          graded.name.c_str(), taken, scene.width, scene.height, rule);
            return message;
        } catch (const std::exception&) {
            // A scene that does not render is that scene's error, said when it is rendered.
        }
    }
    return "";
}

// The stage a C++ function belongs to ("stage/function"): the graded
// stage's, or another stage's of a self-check's tree (its grading.json).
std::string cppStub(const std::string& function, const StageManifest& manifest, const std::string& root) {
    if (std::count(manifest.cppFunctions.begin(), manifest.cppFunctions.end(), function)) return manifest.stage + "/" + function;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(root, ec)) {
        std::ifstream in(entry.path() / "grading.json");
        const nlohmann::json m = nlohmann::json::parse(in, nullptr, false);
        if (m.is_object() && m.contains("cpp_functions") && m["cpp_functions"].is_array())
            for (const nlohmann::json& f : m["cpp_functions"])
                if (f.is_string() && f.get<std::string>() == function) return entry.path().filename().string() + "/" + function;
    }
    return manifest.stage + "/" + function;
}

// `volumes` outlives `engine`, which keeps the address of the one it draws.
// Each image goes with the stubs it reached. After a runaway loop no scene
// is rendered: each says why.
void renderScenes(const StageManifest& manifest, std::map<std::string, Volume>& volumes, RenderEngine& engine,
                  const std::string& root, WorkerResultWriter& out) {
    const std::string runaway = runawayLoop(manifest, volumes, engine);
    if (!runaway.empty()) out.error("stage", "loop", "runaway", runaway);
    for (const GradedScene& graded : manifest.scenes) {
        if (!runaway.empty()) {
            out.error("scene", graded.name, "runaway", "not rendered: a loop ran away (see the stage's message)");
            continue;
        }
        try {
            const Scene scene = gradingSceneFor(graded, volumes, engine);
            const Image image = engine.render(scene);
            out.image(graded.name, image, stubsReached(engine, scene, image));
        } catch (const NotImplemented& e) {
            out.error("scene", graded.name, errorKind(e), e.what(), {cppStub(e.function(), manifest, root)});
        } catch (const std::exception& e) {
            out.error("scene", graded.name, errorKind(e), e.what());
        }
    }
}

}  // namespace

int gradeWorkerCommand(int argc, char** argv) {
    const std::vector<OptionSpec> specs = {
        {"stage", "S", "the stage"},
        {"manifest-root", "DIR", "where S/grading.json is"},
        {"implementation", "DIR", "the implementation root"},
        {"stage-library", "SO", "C++ stages to load (repeatable, later ones win)"},
        {"graded-library", "SO", "the graded stage's C++, loaded last (with --graded)"},
        {"graded", "", "the stage's own C++ functions come only from --graded-library"}};
    const Args args(specs, argc, argv, 2, "grade-worker");
    for (const char* required : {"stage", "manifest-root", "implementation"})
        if (!args.get(required)) throw Error(std::string("grade-worker: --") + required + " is required");
    if (fcntl(3, F_GETFD) == -1)
        throw Error("grade-worker: no results channel on file descriptor 3 (it is started by voxlab grade)");
    const std::string stage = *args.get("stage"), implementation = *args.get("implementation");
    const StageManifest manifest = loadStageManifest(*args.get("manifest-root"), stage);
    for (const std::string& library : args.getAll("stage-library")) loadStageLibrary(library);
    if (args.has("graded")) {
        // The graded stage's C++ answers from a process of its own (stage_host.h).
        clearStageFunctions(manifest.cppFunctions);
        if (args.get("graded-library"))
            useStageHost(stageHostProgram(), *args.get("graded-library"), manifest.cppFunctions);
    } else if (args.get("graded-library")) {
        loadStageLibrary(*args.get("graded-library"));
    }

    WorkerResultWriter out(3);
    auto context = createHeadlessContext();
    // The engine lives until the checks are done, as the GL context does.
    std::map<std::string, Volume> volumes;
    RenderEngine engine(rendererRegistry(), implementation);
    engine.setCountingByUniform(true);  // the runaway-loop check reuses the render's program
    engine.setCompileOnce(true);  // a scene's program draws once or twice: compiling is most of its time
    engine.setExactFiltering(true);  // verdicts that hold on any conforming GL (voxlab/filtering.glsl)
    renderScenes(manifest, volumes, engine, implementation, out);
    for (const GradedCheck& check : manifest.checks) {
        try {
            out.check(check.name, runFunctionCheck(check.name, implementation));
        } catch (const std::exception& e) {
            out.error("check", check.name, errorKind(e), e.what());
        }
    }
    std::cout << "gl: " << context->description() << "\n";
    return 0;
}

}  // namespace voxlab::cli
