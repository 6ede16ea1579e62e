// voxlab render: one image from a scene and/or flags, headless.
#include <chrono>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "voxlab/error.h"
#include "voxlab/gl_context.h"
#include "voxlab/grading.h"
#include "voxlab/render_engine.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume.h"

namespace voxlab::cli {
namespace {

std::vector<OptionSpec> renderOptions() {
    std::vector<OptionSpec> specs = sceneOptions();
    specs.push_back({"out", "PNG", "output file (default: DATASET_RENDERER.png here)"});
    specs.push_back({"implementation", "DIR", "stage shaders from DIR instead of reference/ (a submission)"});
    specs.push_back({"gl", "BACKEND", "headless OpenGL: auto (default, $VOXLAB_GL or osmesa), osmesa, egl"});
    specs.push_back({"exact-filtering", "", "filter between texels in float, as the grader does (voxlab/filtering.glsl)"});
    specs.push_back({"print-scene", "", "print the resolved scene as JSON and render nothing"});
    specs.push_back({"verbose", "", "print the OpenGL renderer and timings"});
    specs.push_back({"help", "", "show this help"});
    return specs;
}

std::string stem(const std::string& path) {
    std::string s = path.substr(path.find_last_of("/:") + 1);
    const std::size_t dot = s.find('.');
    return dot == std::string::npos ? s : s.substr(0, dot);
}

}  // namespace

int renderCommand(int argc, char** argv) {
    const auto specs = renderOptions();
    const Args args(specs, argc, argv, 2, "render");
    if (auto status = usageExit(args, false,
                                "usage: voxlab render [SCENE.json] [options]\n\n"
                                "Renders one image headless and writes it as PNG. Flags override the scene file.\n\n",
                                specs))
        return *status;
    const Scene scene = sceneFromArgs(args, "render");
    if (args.has("print-scene")) {
        std::cout << scene.toJson().dump(2) << "\n";
        return 0;
    }
    const std::string out = args.get("out").value_or(stem(scene.dataset) + "_" + scene.renderer + ".png");
    const Renderer& renderer = rendererRegistry().get(scene.renderer);
    renderer.resolveParameters(scene.parameters);  // report bad parameters before any heavy work
    if (scene.cuttingPlane && scene.cuttingPlane->otherRenderer != "none")
        rendererRegistry().get(scene.cuttingPlane->otherRenderer).resolveParameters(scene.cuttingPlane->otherParameters);

    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const Volume volume = loadVolume(scene.dataset);
    const auto t1 = Clock::now();
    auto context = createHeadlessContext(parseHeadlessBackend(args.get("gl").value_or("auto")));
    RenderEngine engine(rendererRegistry(), args.get("implementation").value_or(""));
    engine.setExactFiltering(args.has("exact-filtering"));
    engine.setVolume(volume);
    const auto t2 = Clock::now();
    const Image image = engine.render(scene);
    // A starter code's checkerboard, explained: the stubs its pixels reached.
    const std::string missing = missingFunctionsNotice(stubsReached(engine, scene, image));
    if (!missing.empty()) std::fprintf(stderr, "voxlab: %s\n", missing.c_str());
    const auto t3 = Clock::now();
    savePng(image, out);

    auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
    if (args.has("verbose")) {
        std::cerr << "gl: " << context->description() << "\n"
                  << "load " << ms(t1 - t0) << " ms, upload " << ms(t2 - t1) << " ms, render " << ms(t3 - t2)
                  << " ms\n";
    }
    std::cout << out << "\n";
    return 0;
}

}  // namespace voxlab::cli
