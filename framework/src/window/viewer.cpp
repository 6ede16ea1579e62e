// voxlab: the interactive viewer. The frame loop and the mouse and keys;
// see viewer_state.h for how the rest is split.
#include "voxlab_gl.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "viewer_script_runner.h"
#include "viewer_state.h"
#include "voxlab/camera_controller.h"
#include "voxlab/error.h"
#include "voxlab/stage_registry.h"
#include "voxlab/viewer.h"
#include "voxlab/window.h"

namespace voxlab {
namespace viewer {
namespace {

// The GLSL version line ImGui's OpenGL 3 backend writes in its shaders.
#ifdef __EMSCRIPTEN__
constexpr const char* kImGuiGlslVersion = "#version 300 es";
#else
constexpr const char* kImGuiGlslVersion = "#version 330 core";
#endif

State* g_state = nullptr;  // for GLFW's drop callback, which has no user pointer of ours

}  // namespace

void keyEvent(GLFWwindow* window, int key, int scancode, int action, int mods) {
    ImGui_ImplGlfw_KeyCallback(window, key, scancode, action, mods);
    if (action == GLFW_PRESS && g_state) g_state->keyPresses.emplace_back(key, mods);
}

namespace {

void onDrop(GLFWwindow*, int count, const char** paths) {
    if (!g_state) return;
    for (int i = 0; i < count; ++i) g_state->dropped.push_back(paths[i]);
}

// The pixel of the rendered image under window point (x, y) (window
// coordinates, which differ from framebuffer pixels on high-DPI screens).
glm::ivec2 imagePixel(const State& s, double x, double y, GLFWwindow* window) {
    int ww, wh;
    glfwGetWindowSize(window, &ww, &wh);
    const double fx = ww > 0 ? double(s.fbWidth) / ww : 1.0, fy = wh > 0 ? double(s.fbHeight) / wh : 1.0;
    return {int(std::floor(x * fx)), int(std::floor(y * fy))};
}

void handleMouse(GLFWwindow* window, State& s) {
    const ImGuiIO& io = ImGui::GetIO();
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool other = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                       glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    const glm::ivec2 px = imagePixel(s, x, y, window);
    const bool nearDivider = s.split == SplitMode::Split && std::abs(px.x - s.divider * s.fbWidth) < 8 * s.contentScale;
    const bool startable =
        !io.WantCaptureMouse && !s.dragging && !s.panning && !s.draggingDivider && s.draggingPlane < 0;
    const int plane = startable && left && !shift ? clipPlaneAt(s, x, y) : -1;
    if (plane >= 0) s.draggingPlane = plane;
    else if (startable && left && nearDivider) s.draggingDivider = true;
    else if (startable && left && !shift) s.dragging = true, s.pressX = x, s.pressY = y, s.moved = false;
    else if (startable && (other || (left && shift))) s.panning = true, s.moved = true;

    const double dx = x - s.lastX, dy = y - s.lastY;
    const glm::ivec2 last = imagePixel(s, s.lastX, s.lastY, window);
    if (s.draggingPlane >= 0) {  // a clip plane's handle: along the plane's normal
        if (dx != 0 || dy != 0) {
            dragClipPlane(s, s.draggingPlane, dx, dy);
            s.dirty = true;
            s.lastInput = Clock::now();
        }
        if (!left) s.draggingPlane = -1;
    }
    if (s.draggingDivider) {
        s.divider = std::clamp(float(px.x) / float(std::max(1, s.fbWidth)), 0.02f, 0.98f);
        if (!left) s.draggingDivider = false;
    }
    if (s.dragging) {
        if (std::abs(x - s.pressX) + std::abs(y - s.pressY) > 3) s.moved = true;
        if (s.moved && (dx != 0 || dy != 0)) {
            orbitCamera(&s.scene.camera, s.volume->extent(), px.x - last.x, px.y - last.y, s.fbWidth, s.fbHeight);
            s.dirty = true;
            s.lastInput = Clock::now();
        }
        if (!left) {
            if (!s.moved && s.showProfile) pickRayProfile(s, px);  // a click, not a drag
            s.dragging = false;
        }
    }
    if (s.panning) {
        if (dx != 0 || dy != 0) {
            panCamera(&s.scene.camera, s.volume->extent(), px.x - last.x, px.y - last.y, s.fbWidth, s.fbHeight);
            s.dirty = true;
            s.lastInput = Clock::now();
        }
        if (!left && !other) s.panning = false;
    }
    s.lastX = x, s.lastY = y;
    if (io.MouseWheel != 0.0f && !io.WantCaptureMouse) {
        zoomCamera(&s.scene.camera, io.MouseWheel);
        s.dirty = true;
        s.lastInput = Clock::now();
    }
}

// I: the left side's implementation, student or reference.
void switchImplementation(State& s) {
    if (!s.hasReference) {
        s.say("a student release has no reference: split view (S) compares a grading scene with its expected image", 3.0);
        return;
    }
    try {
        setImplementation(s.main, s.main.implementation.empty() ? s.studentRoot : "", *s.volume);
        s.say(std::string("left side: ") + (s.main.implementation.empty() ? "reference" : "student"), 2.0);
    } catch (const Error& e) {
        s.say(e.what());
    }
    s.dirty = true;
}

// One key press (GLFW's key code and modifiers).
void handleKey(State& s, int key, int mods) {
    const ImGuiIO& io = ImGui::GetIO();
    const auto& all = rendererRegistry().all();
    if (key >= GLFW_KEY_1 && key < GLFW_KEY_1 + std::min(9, int(all.size())))
        s.scene.renderer = all[std::size_t(key - GLFW_KEY_1)]->id(), s.scene.parameters.clear(), s.dirty = true;
    const bool shift = (mods & GLFW_MOD_SHIFT) != 0, ctrl = (mods & GLFW_MOD_CONTROL) != 0;
    switch (key) {
        case GLFW_KEY_R: reloadShaders(s); break;
        case GLFW_KEY_S: s.split = SplitMode((int(s.split) + 1) % 3), s.dirty = true; break;
        case GLFW_KEY_I: switchImplementation(s); break;
        case GLFW_KEY_X: setAxisView(&s.scene.camera, shift ? "-x" : "+x"), s.dirty = true; break;
        case GLFW_KEY_Y: if (!ctrl) setAxisView(&s.scene.camera, shift ? "-y" : "+y"), s.dirty = true; break;
        case GLFW_KEY_Z: if (!ctrl) setAxisView(&s.scene.camera, shift ? "-z" : "+z"), s.dirty = true; break;
        case GLFW_KEY_O:
            s.scene.camera.projection = s.scene.camera.projection == Projection::Orthographic ? Projection::Perspective
                                                                                              : Projection::Orthographic;
            s.dirty = true;
            break;
        case GLFW_KEY_SPACE: resetCamera(&s.scene.camera), s.dirty = true; break;
        case GLFW_KEY_H: case GLFW_KEY_F1: s.showHelp = !s.showHelp; break;
        case GLFW_KEY_T: s.showTransferFunction = !s.showTransferFunction; break;
        case GLFW_KEY_L: s.showSlices = !s.showSlices; break;
        case GLFW_KEY_F: s.showProfile = !s.showProfile; break;
        case GLFW_KEY_TAB: s.showPanel = !s.showPanel; break;
        case GLFW_KEY_P: s.screenshotRequest = timestampedScreenshotName(), s.screenshotByKey = true; break;
        case GLFW_KEY_ESCAPE: s.showHelp = false; break;
        // Presentation mode: + and - (also on the keypad) scale the whole UI.
        case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: s.requestedUiScale = std::max(s.requestedUiScale, s.uiScale) + 0.25f; break;
        case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT:
            s.requestedUiScale = (s.requestedUiScale > 0.0f ? s.requestedUiScale : s.uiScale) - 0.25f;
            break;
        default: break;
    }
    // A deck: the arrows (and a presenter's clicker, which sends Page Up/Down).
    // (Not while the mouse is over a panel: the slice views take the arrows there.)
    if (s.deck && !io.WantCaptureMouse) {
        const int last = int(s.deck->slides.size()) - 1;
        int to = s.slide;
        if (key == GLFW_KEY_RIGHT || key == GLFW_KEY_DOWN || key == GLFW_KEY_PAGE_DOWN) to = std::min(last, to + 1);
        if (key == GLFW_KEY_LEFT || key == GLFW_KEY_UP || key == GLFW_KEY_PAGE_UP) to = std::max(0, to - 1);
        if (key == GLFW_KEY_HOME) to = 0;
        if (key == GLFW_KEY_END) to = last;
        if (to != s.slide) showSlide(s, to);
    }
}

// Every key pressed since the last frame, in order, each once: also those
// released again before this frame began (a long frame, a slide's load).
void handleKeys(State& s) {
    std::vector<std::pair<int, int>> presses;
    presses.swap(s.keyPresses);
    if (ImGui::GetIO().WantCaptureKeyboard) return;  // typed into a field
    for (const auto& [key, mods] : presses) handleKey(s, key, mods);
}

void loadDropped(State& s) {
    std::vector<std::string> files;
    files.swap(s.dropped);
    for (const std::string& f : files) {
        try {
            loadDataset(s, f);
            s.say("opened " + f, 2.5);
        } catch (const std::exception& e) {
            s.say(e.what(), 8.0);  // a bad file is a message, never a crash
        }
    }
}

// High-DPI: ImGui's sizes and font follow the window's content scale
// (times the presentation scale, viewer_style.cpp).
float windowContentScale(GLFWwindow* window) {
    float sx = 1.0f, sy = 1.0f;
#ifndef __EMSCRIPTEN__  // (emscripten's GLFW is 3.2: the page's canvas is drawn at CSS pixels)
    glfwGetWindowContentScale(window, &sx, &sy);
#else
    (void)window;
#endif
    return std::max(1.0f, std::max(sx, sy));
}

// Saves the screenshot asked for this frame (P, the button or a script's
// step). In the window a failure is shown for a while; a script's
// screenshots are its output, so there a failure ends the script: the
// one-line error is printed and false returned.
bool saveRequestedScreenshot(State& s, bool script) {
    if (s.screenshotRequest.empty()) return true;
    const std::string path = s.screenshotRequest;
    s.screenshotRequest.clear();
    try {
        saveWindowScreenshot(s.fbWidth, s.fbHeight, path);
        const bool byKey = s.screenshotByKey;
        s.screenshotByKey = false;
        if (script && !byKey) {  // a script's output; nothing over the window (its next screenshot)
            std::printf("%s\n", path.c_str()), std::fflush(stdout);
            return true;
        }
        // P: where it went, absolute, in a message and for a while on the status line.
        std::error_code ec;
        const std::filesystem::path where = std::filesystem::absolute(path, ec);
        s.lastScreenshot = ec ? path : where.lexically_normal().string();
        s.lastScreenshotUntil = Clock::now() + std::chrono::seconds(20);
        s.say("screenshot saved: " + std::filesystem::path(path).filename().string() + " (the full path: bottom right)", 6.0);
        if (script) std::printf("screenshot saved: %s\n", s.lastScreenshot.c_str()), std::fflush(stdout);
    } catch (const Error& e) {
        if (script) return std::fprintf(stderr, "voxlab: %s\n", e.what()), false;
        s.say(e.what(), 6.0);
    }
    return true;
}

// One frame: input, panels and overlays, the images, the UI drawn over them.
// A scale asked for by a key is applied first, between frames, since the
// font atlas is rebuilt.
void drawFrame(State& s, GLFWwindow* window) {
    if (s.requestedUiScale > 0.0f) {
        applyUiScale(s, s.requestedUiScale, s.windowScale);
        s.requestedUiScale = 0.0f;
        s.say("UI scale " + std::to_string(int(s.uiScale * 100 + 0.5f)) + "% (+ and - keys)", 2.0);
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handleMouse(window, s);
    handleKeys(s);
    drawPanels(s);
    drawOverlays(s);
    s.relayout = false;
    renderFrame(s);
    presentFrame(s);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

// GL objects go while the context still exists, then ImGui.
void shutDown(State& s) {
    for (Side* side : {&s.main, &s.other}) side->engine.reset(), side->coarse.reset();
    s.sliceViewer.reset();
    s.presenter.reset();
    releaseTransferFunctionEditorTextures();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

}  // namespace
}  // namespace viewer

// A viewer between frames: its state, its window and the script driving it.
// The native loop and the browser's main loop (web/main_web.cpp) both call
// stepViewer once a frame.
struct ViewerSession {
    ViewerOptions options;
    GlfwWindow window;
    viewer::State s;
    std::unique_ptr<viewer::ScriptRunner> script;
    int frame = 0;
    int exitCode = 0;
    ViewerSession(const ViewerOptions& o) : options(o), window(o.width, o.height, "voxlab") {}
};

ViewerSession* startViewer(const Scene& initial, const ViewerOptions& options) {
    using namespace viewer;
    auto volume = std::make_unique<Volume>(loadVolume(initial.dataset));
    auto session = std::make_unique<ViewerSession>(options);
    State& s = session->s;
    GlfwWindow& window = session->window;
    s.scene = initial;
    s.scenePath = options.scenePath;
    s.studentRoot = options.studentRoot.empty() ? projectRoot() + "/assignments" : options.studentRoot;
    s.hasReference = defaultImplementationRoot() == projectRoot() + "/reference";
    s.deck = options.deck;
    setImplementation(s.main, options.implementationRoot, *volume);
    s.volume = std::move(volume);
    resetCoarseLevel(s);
    s.slices = initialSliceCursor(*s.volume);
    s.tfPath = presetOf(s.scene, *s.volume);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini litter in the working folder
    ImGui_ImplGlfw_InitForOpenGL(window.handle(), true);
    ImGui_ImplOpenGL3_Init(kImGuiGlslVersion);
    s.windowScale = windowContentScale(window.handle());
    applyUiScale(s, options.uiScale, s.windowScale);
    if (s.deck) {  // a lecture starts with the image alone: Tab and T bring the panels back
        s.showPanel = s.showTransferFunction = false;
        showSlide(s, 0);
    }
    g_state = &s;
    glfwSetDropCallback(window.handle(), onDrop);
    glfwSetKeyCallback(window.handle(), keyEvent);  // ImGui's, with every press kept for handleKeys
    glfwSwapInterval(options.script.empty() ? 1 : 0);
    if (!options.script.empty()) session->script = std::make_unique<ScriptRunner>(options.script);
    return session.release();
}

// One frame; false once the viewer is done (its exit code is then set).
bool stepViewer(ViewerSession& session) {
    using namespace viewer;
    State& s = session.s;
    GLFWwindow* window = session.window.handle();
    const ViewerOptions& options = session.options;
    if (glfwWindowShouldClose(window)) return false;
    glfwPollEvents();
    const auto frameStart = Clock::now();
    glfwGetFramebufferSize(window, &s.fbWidth, &s.fbHeight);
    // (A student release comparing with an expected image renders at that image's size.)
    if ((s.fbWidth != s.imageWidth || s.fbHeight != s.imageHeight) && !comparesWithExpected(s)) s.dirty = s.dirty || !s.interactive;
    if (session.script) {
        try {
            if (session.script->step(s, window) == ScriptRunner::Done) {
                if (!options.keepOpen) return false;
                session.script.reset();  // the prepared state is the lecturer's now
                glfwSwapInterval(1);
            }
        } catch (const Error& e) {
            std::fprintf(stderr, "voxlab: %s\n", e.what());
            session.exitCode = 1;
            return false;
        }
    }
    loadDropped(s);
    drawFrame(s, window);
    ++session.frame;
    if (!saveRequestedScreenshot(s, session.script != nullptr)) {
        session.exitCode = 1;
        return false;
    }
    if (!options.screenshot.empty() && session.frame >= std::max(options.frames, 2)) {
        saveWindowScreenshot(s.fbWidth, s.fbHeight, options.screenshot);
        std::printf("%s\n", options.screenshot.c_str());
        return false;
    }
    glfwSwapBuffers(window);
    s.frameMs = std::chrono::duration<double, std::milli>(Clock::now() - frameStart).count();
    return true;
}

int finishViewer(ViewerSession* session) {
    viewer::g_state = nullptr;
    viewer::shutDown(session->s);
    const int exitCode = session->exitCode;
    delete session;
    return exitCode;
}

void viewerShowScene(ViewerSession& session, const std::string& scenePath, const std::string& implementationRoot) {
    viewer::State& s = session.s;
    const Scene scene = Scene::load(scenePath);
    if (implementationRoot != s.main.implementation) viewer::setImplementation(s.main, implementationRoot, *s.volume);
    s.main.renderer.clear();  // the scene's renderer
    viewer::setScene(s, scene, scenePath);
}

void viewerReloadShaders(ViewerSession& session) { viewer::reloadShaders(session.s); }

void viewerResize(ViewerSession& session, int width, int height) {
    if (width > 0 && height > 0) glfwSetWindowSize(session.window.handle(), width, height);
}

void viewerOpen(ViewerSession& session, const std::string& path) { session.s.dropped.push_back(path); }

std::string viewerError(const ViewerSession& session) {
    const viewer::Side& side = session.s.main;
    if (!side.error.empty()) return side.error;
    return side.engine ? side.engine->shaderError() : std::string();
}

std::string viewerDataset(const ViewerSession& session) { return session.s.scene.dataset; }

double viewerRenderMs(const ViewerSession& session) { return session.s.renderMs; }

int runViewer(const Scene& initial, const ViewerOptions& options) {
    ViewerSession* session = startViewer(initial, options);
    const viewer::State& s = session->s;
    try {
        while (stepViewer(*session)) {
            // Idle: nothing to render and no input; don't spin the CPU.
            if (!session->script && !s.dirty && !s.interactive && !s.dragging && !s.panning)
                glfwWaitEventsTimeout(0.25);
        }
    } catch (...) {  // the window and ImGui are released before the error goes on
        finishViewer(session);
        throw;
    }
    return finishViewer(session);
}

}  // namespace voxlab
