// voxlab grade-worker: the child process that runs one stage of one
// implementation for the grader (grader.h). Not meant to be run by hand.
//
// It renders each of the stage's grading scenes to OUT/NAME{suffix}.png and
// runs each function check into OUT/checks/NAME{suffix}.json. A scene or
// check that fails writes NAME{suffix}.error.json instead:
// {"kind": "compile_error" | "not_implemented" | "error", "message": "..."}.
// Work that hangs or crashes is the parent's to notice.
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
#include "voxlab/render_engine.h"
#include "voxlab/shader.h"
#include "voxlab/stage_library.h"
#include "voxlab/volume.h"

namespace voxlab::cli {

namespace {

namespace fs = std::filesystem;

void writeError(const fs::path& path, const std::exception& e) {
    std::string kind = "error";
    if (dynamic_cast<const ShaderError*>(&e)) kind = "compile_error";
    if (dynamic_cast<const NotImplemented*>(&e)) kind = "not_implemented";
    std::ofstream(path) << nlohmann::json{{"kind", kind}, {"message", e.what()}}.dump(2) << "\n";
}

}  // namespace

int gradeWorkerCommand(int argc, char** argv) {
    const std::vector<OptionSpec> specs = {
        {"stage", "S", "the stage"},
        {"manifest-root", "DIR", "where S/grading.json is"},
        {"implementation", "DIR", "the implementation root"},
        {"out", "DIR", "output folder"},
        {"suffix", "TEXT", "appended to output names"},
        {"stage-library", "SO", "C++ stages to load (repeatable, later ones win)"}};
    const Args args(specs, argc, argv, 2, "grade-worker");
    for (const char* required : {"stage", "manifest-root", "implementation", "out"})
        if (!args.get(required)) throw Error(std::string("grade-worker: --") + required + " is required");
    const std::string stage = *args.get("stage"), suffix = args.get("suffix").value_or("");
    const fs::path out = *args.get("out");
    const std::string implementation = *args.get("implementation");
    const StageManifest manifest = loadStageManifest(*args.get("manifest-root"), stage);
    for (const std::string& library : args.getAll("stage-library")) loadStageLibrary(library);

    auto context = createHeadlessContext();
    RenderEngine engine(implementation);
    std::map<std::string, Volume> volumes;
    for (const GradedScene& graded : manifest.scenes) {
        try {
            Scene scene = Scene::load(graded.scenePath);
            // Grading renders every sample a submission asks for: skipping
            // trusts the sampling and gradient stages to read only nearby
            // voxels, which a faulty submission need not do.
            scene.skipEmptySpace = false;
            auto found = volumes.find(scene.dataset);
            if (found == volumes.end()) found = volumes.emplace(scene.dataset, loadVolume(scene.dataset)).first;
            engine.setVolume(found->second);
            savePng(engine.render(scene), (out / (graded.name + suffix + ".png")).string());
        } catch (const std::exception& e) {
            writeError(out / (graded.name + suffix + ".error.json"), e);
        }
    }
    if (!manifest.checks.empty()) fs::create_directories(out / "checks");
    for (const GradedCheck& check : manifest.checks) {
        try {
            const nlohmann::json result = runFunctionCheck(check.name, implementation);
            std::ofstream(out / "checks" / (check.name + suffix + ".json")) << result.dump() << "\n";
        } catch (const std::exception& e) {
            writeError(out / "checks" / (check.name + suffix + ".error.json"), e);
        }
    }
    std::cout << "gl: " << context->description() << "\n";
    return 0;
}

}  // namespace voxlab::cli
