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
#include "voxlab/grading.h"
#include "voxlab/self_check.h"
#include "voxlab/scene.h"
#include "voxlab/viewer.h"

namespace {

voxlab::ViewerSession* g_session = nullptr;

int g_frames = 0;

// The viewer could not start or a frame failed: the native viewer would exit
// with this line; the page shows it too (workbench.js: voxlabStopped).
void sayStopped(const char* why) {
    std::fprintf(stderr, "voxlab: %s\n", why);
    EM_ASM({ if (Module.voxlabStopped) Module.voxlabStopped(UTF8ToString($0)); }, why);
}

void frame() {
    if (!g_session) return;
    bool more = false;
    try {
        more = voxlab::stepViewer(*g_session);
    } catch (const std::exception& e) {
        sayStopped(e.what());
    }
    // The page (and its test) watch this count to know a frame is on screen.
    EM_ASM({ Module.voxlabFrames = $0; }, ++g_frames);
    if (!more) {
        voxlab::finishViewer(g_session);
        g_session = nullptr;
        emscripten_cancel_main_loop();
    }
}

// The page's calls (web/shell/workbench.js, through Module.ccall). Strings
// returned stay valid until the next call.
std::string g_reply;

const char* reply(std::string text) {
    g_reply = std::move(text);
    return g_reply.c_str();
}

std::string stageTree(int student) { return voxlab::projectRoot() + (student ? "/assignments" : "/reference"); }

}  // namespace

extern "C" {

// Shows the stage's first grading scene, rendered by the student's files
// (assignments/) or the model (reference/). Returns "" or the error.
EMSCRIPTEN_KEEPALIVE const char* vx_show_stage(const char* stage, int student) {
    using namespace voxlab;
    try {
        const StageManifest manifest = loadStageManifest(stageTree(student), stage);
        for (const GradedScene& scene : manifest.scenes)
            if (!scene.hidden) {
                // (The viewer names the reference by an empty folder, as its switch does.)
                if (g_session) viewerShowScene(*g_session, scene.scenePath, student ? stageTree(1) : "");
                return reply("");
            }
        return reply(std::string(stage) + ": no grading scene to show");
    } catch (const std::exception& e) {
        return reply(e.what());
    }
}

// Compiles the stage files again (after the page wrote them) and renders.
EMSCRIPTEN_KEEPALIVE void vx_reload() {
    if (g_session) voxlab::viewerReloadShaders(*g_session);
}

// The main view's error (file:line for a compiler's message), or "".
EMSCRIPTEN_KEEPALIVE const char* vx_error() { return reply(g_session ? voxlab::viewerError(*g_session) : ""); }

// The canvas's new size in CSS pixels (the page's layout changed).
EMSCRIPTEN_KEEPALIVE void vx_resize(int width, int height) {
    if (g_session) voxlab::viewerResize(*g_session, width, height);
}

// Opens a dataset or scene file of the page's file system, as a drop would.
EMSCRIPTEN_KEEPALIVE void vx_open(const char* path) {
    if (g_session) voxlab::viewerOpen(*g_session, path);
}

// The dataset on screen (a path in the page's file system).
EMSCRIPTEN_KEEPALIVE const char* vx_dataset() { return reply(g_session ? voxlab::viewerDataset(*g_session) : ""); }

// How long the image on screen took to render, in milliseconds.
EMSCRIPTEN_KEEPALIVE double vx_render_ms() { return g_session ? voxlab::viewerRenderMs(*g_session) : 0.0; }

// The self-check of one stage (self_check.h), as JSON.
EMSCRIPTEN_KEEPALIVE const char* vx_self_check(const char* stage, int student) {
    using namespace voxlab;
    try {
        SelfCheckOptions options{stageTree(student), projectRoot() + "/expected", "/tmp/self-check/" + std::string(stage)};
        return reply(selfCheckStage(stage, options).dump());
    } catch (const std::exception& e) {
        return reply(nlohmann::json{{"stage", stage}, {"status", "error"}, {"message", e.what()}}.dump());
    }
}

}  // extern "C"

int main(int argc, char** argv) {
    using namespace voxlab;
    const std::string scenePath = argc > 1 ? argv[1] : projectRoot() + "/datasets/scenes/default.json";
    try {
        ViewerOptions options;
        options.width = EM_ASM_INT({ return Module.canvas.clientWidth || 960; });
        options.height = EM_ASM_INT({ return Module.canvas.clientHeight || 640; });
        g_session = startViewer(Scene::load(scenePath), options);
    } catch (const Error& e) {
        sayStopped(e.what());
        return 1;
    }
    // The browser calls frame() once per display refresh; main returns at once
    // and the module stays alive.
    emscripten_set_main_loop(frame, 0, false);
    return 0;
}
