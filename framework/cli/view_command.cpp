// voxlab view: the interactive viewer on a dataset or scene.
#include <iostream>
#include <utility>

#include "commands.h"
#include "voxlab/error.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume.h"
#ifdef VOXLAB_HAVE_VIEWER
#include "voxlab/deck.h"
#include "voxlab/renderers.h"
#include "voxlab/viewer.h"
#endif

namespace voxlab::cli {

int viewCommand(int argc, char** argv) {
    std::vector<OptionSpec> specs = sceneOptions();
    specs.push_back({"implementation", "DIR", "stage shaders from DIR instead of reference/"});
    specs.push_back({"student", "DIR", "the implementation switch's student side (default: assignments/)"});
    specs.push_back({"script", "FILE", "play a viewer script (load, renderer, rotate, split, screenshot, ...) and exit"});
    specs.push_back({"keep-open", "", "after --script, leave the window open for a person (a prepared demo)"});
    specs.push_back({"deck", "FILE", "a demo deck: slides of scenes and captions, stepped with the arrow keys"});
    specs.push_back({"ui-scale", "X", "presentation mode: the UI's size, 0.75 to 4 (keys + and -; 2 for a hall)"});
    specs.push_back({"screenshot", "PNG", "render a few frames, save the window to PNG and exit"});
    specs.push_back({"frames", "N", "frames to render before --screenshot (default 3)"});
    specs.push_back({"window-size", "WxH", "window size (default 1280x800)"});
    specs.push_back({"help", "", "show this help"});
    const int first = (argc > 1 && std::string(argv[1]) == "view") ? 2 : 1;
    const Args args(specs, argc, argv, first, "view");
    if (auto status = usageExit(args, false,
                                "usage: voxlab view [DATASET|SCENE.json] [options]\n\n"
                                "Opens the interactive viewer. With no argument it shows the default scene.\n"
                                "In the window, H lists the keys. --script FILE drives it without a person (see\n"
                                "framework/include/scene/voxlab/viewer_script.h) and exits at the end of the script, or\n"
                                "hands the window over with --keep-open. --deck FILE steps through a lecture's\n"
                                "scenes with the arrow keys (the format: framework/include/scene/voxlab/deck.h).\n\n",
                                specs))
        return *status;
#ifdef VOXLAB_HAVE_VIEWER
    // With no argument the viewer opens the default scene; a dataset given
    // as the argument replaces the default scene's dataset (and its
    // dataset-specific window and transfer function).
    const auto& pos = args.positionals();
    const bool sceneFile = !pos.empty() && pos[0].size() > 5 && pos[0].substr(pos[0].size() - 5) == ".json";
    std::optional<Scene> base;
    if (!sceneFile && !args.has("dataset")) {
        base = Scene::load(defaultScenePath());
        if (!pos.empty()) {
            base->dataset = resolveDataPath(pos[0]);
            base->window.reset();
            base->transferFunction.reset();
        }
    }
    ViewerOptions options;
    if (sceneFile) options.scenePath = pos[0];  // a grading scene's expected image is found by its file
    if (auto deckFile = args.get("deck")) {  // checked whole before any window opens
        Deck deck = loadDeck(*deckFile);
        for (std::size_t i = 0; i < deck.slides.size(); ++i)
            if (!rendererRegistry().find(deck.slides[i].scene.renderer))
                throw Error(*deckFile + ": slide " + std::to_string(i + 1) + ": renderer '" +
                            deck.slides[i].scene.renderer + "' is not known (voxlab list)");
        if (!pos.empty() || args.has("dataset")) throw Error("view: --deck gives the scenes; no dataset or scene too");
        base = deck.slides[0].scene;
        options.deck = std::move(deck);
    }
    const Scene scene = sceneFromArgs(args, "view", base ? &*base : nullptr);
    options.implementationRoot = args.get("implementation").value_or("");
    options.studentRoot = args.get("student").value_or("");
    options.script = args.get("script").value_or("");
    options.keepOpen = args.has("keep-open");
    if (options.keepOpen && options.script.empty()) throw Error("view: --keep-open goes with --script FILE");
    if (auto scale = args.get("ui-scale")) {
        const double x = parseNumber(*scale, "--ui-scale");
        if (!(x >= 0.75 && x <= 4.0)) throw Error("option --ui-scale: expected a number from 0.75 to 4, got '" + *scale + "'");
        options.uiScale = float(x);
    }
    options.screenshot = args.get("screenshot").value_or("");
    options.frames = args.get("frames") ? parseInt(*args.get("frames"), "--frames") : 3;
    if (auto ws = args.get("window-size")) {
        const std::size_t x = ws->find('x');
        if (x == std::string::npos) throw Error("option --window-size: expected WxH");
        options.width = parseInt(ws->substr(0, x), "--window-size");
        options.height = parseInt(ws->substr(x + 1), "--window-size");
    }
    return runViewer(scene, options);
#else
    throw Error("view: this build has no viewer (configured with VOXLAB_WITH_VIEWER=OFF)");
#endif
}

}  // namespace voxlab::cli
