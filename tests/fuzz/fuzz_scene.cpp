// libFuzzer target: scene files (Scene::load on a .json file).
//
// The input is the scene's JSON text. Relative paths in it resolve against
// the scratch folder, then $VOXLAB_DATA_PATH, then the project's datasets/
// (so the seeds' "bonsai.nrrd" and "tf/bonsai.json" are found; volumes are
// not loaded by Scene::load). Seeds: datasets/scenes/*.json,
// tests/golden/scenes/*.json and the renderers' grading scenes.
// Besides the error contract (fuzz_common.h), a scene that loads must write
// (toJson) a scene that loads again and writes the same JSON: that is what
// the viewer's "save scene" relies on.
#include <nlohmann/json.hpp>

#include "fuzz_common.h"
#include "voxlab/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string path = fuzz::scratchFile("scene.json");
    fuzz::writeFile(path, std::string(reinterpret_cast<const char*>(data), size));
    fuzz::expectOnlyVoxlabErrors([&] {
        const Scene scene = Scene::load(path);
        const nlohmann::json written = scene.toJson();
        Scene again;
        try {
            again = Scene::fromJson(written, "written", fuzz::scratchDir());
        } catch (const Error& e) {
            fuzz::finding("a loaded scene's toJson() does not load", e.what());
        }
        fuzz::require(again.toJson() == written, "scene round trip changes the scene",
                      written.dump());
    });
    return 0;
}
