// voxlab in the browser: the native viewer's frames driven by the page's
// animation loop. The page (web/shell/index.html) starts the module with the
// scene to show; everything else is the framework as the native build has it.
//
// The project tree the viewer expects (shaders/, reference/, assignments/,
// datasets/) is preloaded under /voxlab in emscripten's in-memory file
// system, which is what VOXLAB_SOURCE_DIR names in this build.
#include <emscripten.h>

#include <cstdio>
#include <exception>
#include <string>

#include "voxlab/error.h"
#include "voxlab/scene.h"
#include "voxlab/viewer.h"

namespace {

voxlab::ViewerSession* g_session = nullptr;

int g_frames = 0;

void frame() {
    if (!g_session) return;
    bool more = false;
    try {
        more = voxlab::stepViewer(*g_session);
    } catch (const std::exception& e) {  // the native viewer would exit with this line
        std::fprintf(stderr, "voxlab: %s\n", e.what());
    }
    // The page (and its test) watch this count to know a frame is on screen.
    EM_ASM({ Module.voxlabFrames = $0; }, ++g_frames);
    if (!more) {
        voxlab::finishViewer(g_session);
        g_session = nullptr;
        emscripten_cancel_main_loop();
    }
}

}  // namespace

int main(int argc, char** argv) {
    using namespace voxlab;
    const std::string scenePath = argc > 1 ? argv[1] : projectRoot() + "/datasets/scenes/default.json";
    try {
        ViewerOptions options;
        options.width = EM_ASM_INT({ return Module.canvas.clientWidth || 960; });
        options.height = EM_ASM_INT({ return Module.canvas.clientHeight || 640; });
        g_session = startViewer(Scene::load(scenePath), options);
    } catch (const Error& e) {
        std::fprintf(stderr, "voxlab: %s\n", e.what());
        return 1;
    }
    // The browser calls frame() once per display refresh; main returns at once
    // and the module stays alive.
    emscripten_set_main_loop(frame, 0, false);
    return 0;
}
