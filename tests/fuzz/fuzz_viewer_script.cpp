// libFuzzer target: viewer scripts (parseViewerScript on a script file).
//
// The input is the script's text, one step per line. Seeds: a script with
// every command, and the drag script of docs/performance.md.
// Besides parsing, every parsed step goes through the typed accessors the
// viewer uses (word, number, integer, onOff, dataPath, applyCameraStep):
// they may throw located voxlab::Errors, nothing else (fuzz_common.h).
#include "fuzz_common.h"
#include "voxlab/viewer_script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string path = fuzz::scratchFile("script.vs");
    fuzz::writeFile(path, std::string(reinterpret_cast<const char*>(data), size));
    std::vector<ViewerStep> steps;
    fuzz::expectOnlyVoxlabErrors([&] { steps = parseViewerScript(path); });
    for (const ViewerStep& step : steps) {
        for (int i = 0; i <= int(step.args.size()); ++i) {  // one past the end: "missing argument"
            fuzz::expectOnlyVoxlabErrors([&] { word(step, i); });
            fuzz::expectOnlyVoxlabErrors([&] { number(step, i); });
            fuzz::expectOnlyVoxlabErrors([&] { integer(step, i); });
            fuzz::expectOnlyVoxlabErrors([&] { onOff(step, i); });
        }
        if (step.command == "load" || step.command == "scene" ||
            (step.command == "tf" && step.args.size() == 1 && step.args[0] != "none"))
            fuzz::expectOnlyVoxlabErrors([&] { dataPath(step, 0); });
        if (step.command == "camera") {
            CameraSpec camera;
            fuzz::expectOnlyVoxlabErrors([&] { applyCameraStep(step, &camera); });
        }
    }
    return 0;
}
