// voxlab viewer: executing viewer scripts (see viewer_script_runner.h).
#define GLFW_INCLUDE_NONE
#include "viewer_script_runner.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>

#include "voxlab/camera_controller.h"
#include "voxlab/error.h"
#include "voxlab/stage_registry.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"

namespace voxlab::viewer {

ScriptRunner::ScriptRunner(const std::string& path) : steps_(parseViewerScript(path)) {}

namespace {

int glfwKey(const std::string& name) {
    static const std::pair<const char*, int> keys[] = {
        {"left", GLFW_KEY_LEFT},       {"right", GLFW_KEY_RIGHT},        {"up", GLFW_KEY_UP},
        {"down", GLFW_KEY_DOWN},       {"pageup", GLFW_KEY_PAGE_UP},     {"pagedown", GLFW_KEY_PAGE_DOWN},
        {"home", GLFW_KEY_HOME},       {"end", GLFW_KEY_END},            {"plus", GLFW_KEY_EQUAL},
        {"minus", GLFW_KEY_MINUS},     {"p", GLFW_KEY_P}};
    for (const auto& [n, key] : keys)
        if (name == n) return key;
    return GLFW_KEY_UNKNOWN;  // parsing already refused other names
}

// The steps that change what is rendered: the scene, its data and camera.
// False for any other command.
bool sceneStep(State& s, const ViewerStep& st) {
    const std::string& c = st.command;
    if (c == "load" || c == "scene") {
        loadDataset(s, dataPath(st, 0));
    } else if (c == "renderer") {
        rendererRegistry().get(word(st, 0));  // throws for an unknown id
        s.scene.renderer = word(st, 0);
        s.scene.parameters.clear();
    } else if (c == "param") {
        s.scene.parameters[word(st, 0)] = number(st, 1);
        rendererRegistry().get(s.scene.renderer).resolveParameters(s.scene.parameters);
    } else if (c == "step") {
        s.scene.step = number(st, 0);
    } else if (c == "interpolation") {
        s.scene.interpolation = parseInterpolation(word(st, 0));
    } else if (c == kTransferFunctionName) {
        s.tfPath = word(st, 0) == "none" ? "" : dataPath(st, 0);  // the panel shows its name
        if (word(st, 0) == "none") s.scene.transferFunction.reset();
        else s.scene.transferFunction = TransferFunction::load(s.tfPath);
    } else if (c == kTransferFunction2DName) {
        if (word(st, 0) == "none") s.scene.transferFunction2D.reset();
        else s.scene.transferFunction2D = TransferFunction2D::load(dataPath(st, 0));
    } else if (c == "camera") {
        applyCameraStep(st, &s.scene.camera);
    } else if (c == "rotate") {
        rotateCamera(&s.scene.camera, number(st, 0), number(st, 1));
    } else if (c == "window") {
        s.scene.window = glm::dvec2(number(st, 0), number(st, 1));
    } else if (c == "skipping") {
        s.scene.skipEmptySpace = onOff(st, 0);
    } else if (c == "lod") {
        s.coarseWhileMoving = onOff(st, 0);
    } else {
        return false;
    }
    return true;
}

// The steps that change how the window shows it: split view, sides,
// panels, the ray profile, the UI's scale, a deck's slide. False for any
// other command.
bool viewStep(State& s, const ViewerStep& st) {
    const std::string& c = st.command;
    if (c == "samples") {
        s.showSamples = onOff(st, 0);
    } else if (c == "split") {
        const std::string& m = word(st, 0);
        s.split = m == "on" ? SplitMode::Split : m == "difference" ? SplitMode::Difference : SplitMode::Off;
    } else if (c == "divider") {
        s.divider = float(number(st, 0));
    } else if (c == "implementation") {
        const std::string& which = word(st, 0);
        setImplementation(s.main, which == "reference" ? "" : which == "student" ? s.studentRoot : which, *s.volume);
    } else if (c == "right") {
        s.other.renderer = word(st, 0) == "same" ? "" : word(st, 0);
    } else if (c == "panel") {
        const std::string& p = word(st, 0);
        const bool on = onOff(st, 1);
        if (p == "slices") s.showSlices = on;
        else if (p == kTransferFunctionName || p == kTransferFunction2DName) s.showTransferFunction = on;
        else if (p == "profile") s.showProfile = on;
        else if (p == "help") s.showHelp = on;
        else if (p == "controls") s.showPanel = on;
        else failStep(st, "unknown panel '" + p + "' (" + viewerPanelList() + ")");
    } else if (c == "enlarge") {
        const std::string& v = word(st, 0);
        s.showSlices = true;
        if (!s.sliceViewer) s.sliceViewer = std::make_unique<SliceViewer>();
        s.sliceViewer->enlarged = v == "axial" ? kAxialAxis : v == "coronal" ? kCoronalAxis : v == "sagittal" ? kSagittalAxis : -1;
    } else if (c == "click") {
        pickRayProfile(s, glm::ivec2(integer(st, 0), integer(st, 1)));
    } else if (c == "drag-plane") {
        // Through the handle's hit test, as the mouse would.
        const int index = integer(st, 0) - 1;
        if (index >= int(s.scene.clipPlanes.size()))
            failStep(st, "the scene has " + std::to_string(s.scene.clipPlanes.size()) + " clip planes");
        const ClipPlaneHandle handle = clipPlaneHandles(s)[std::size_t(index)];
        if (!handle.visible || clipPlaneAt(s, handle.centre.x, handle.centre.y) != index)
            failStep(st, "clip plane " + std::to_string(index + 1) + "'s handle cannot be grabbed in this view");
        dragClipPlane(s, index, number(st, 1), number(st, 2));
    } else if (c == "ui-scale") {
        applyUiScale(s, float(number(st, 0)), s.windowScale);
    } else if (c == "slide") {
        if (!s.deck) failStep(st, "no deck is open (voxlab view --deck FILE)");
        if (integer(st, 0) > int(s.deck->slides.size()))
            failStep(st, "the deck has " + std::to_string(s.deck->slides.size()) + " slides");
        showSlide(s, integer(st, 0) - 1);
    } else {
        return false;
    }
    return true;
}

}  // namespace

ScriptRunner::Progress ScriptRunner::step(State& s, GLFWwindow* window) {
    // A key pressed by the last step goes up one frame later, through the
    // same callback GLFW calls, so the viewer sees a person's key press.
    if (heldKey_ != 0) {
        keyEvent(window, heldKey_, 0, GLFW_RELEASE, 0);
        heldKey_ = 0;
        return Continue;
    }
    // `press` and `rendering` do not wait for the image: keys while it renders.
    noteFrame(s);
    if (next_ < steps_.size() && waitFrames_ == 0 && dragFrames_ == 0 && !settling_) {
        if (steps_[next_].command == "press") return press(s, window, steps_[next_++]);
        if (steps_[next_].command == "rendering") return rendering(s, steps_[next_]);
    }
    // A frame is rendered between steps; `wait N` adds N more, and every
    // step waits for a full-quality image first.
    if (waitFrames_ > 0) {
        --waitFrames_;
        return Continue;
    }
    if (dragFrames_ > 0 || settling_) return drag(s);
    if (s.dirty || s.interactive) return Continue;  // (interactive: still refining)
    if (next_ >= steps_.size()) return finished(s);
    const ViewerStep& st = steps_[next_++];
    const std::string& c = st.command;
    try {
        if (sceneStep(s, st) || viewStep(s, st)) {
            // applied: the next frame shows it
        } else if (c == "key") {
            heldKey_ = glfwKey(word(st, 0));
            keyEvent(window, heldKey_, 0, GLFW_PRESS, 0);
            return Continue;  // the viewer's key handling marks what changed
        } else if (c == "drag") {
            dragDx_ = number(st, 0), dragDy_ = number(st, 1), dragFrames_ = integer(st, 2);
            dragTimes_.clear();
            refinements_ = 0;
            return Continue;
        } else if (c == "size") {
            glfwSetWindowSize(window, integer(st, 0), integer(st, 1));
            waitFrames_ = 2;
        } else if (c == "wait") {
            waitFrames_ = integer(st, 0);
        } else if (c == "screenshot") {
            s.screenshotRequest = word(st, 0);
        } else if (c == "quit") {
            return finished(s);
        } else {
            failStep(st, "this viewer cannot run '" + c + "'");
        }
    } catch (const Error& e) {
        const std::string what = e.what();
        if (what.rfind(stepLocation(st), 0) == 0) throw;  // already names the line
        failStep(st, what);
    }
    s.dirty = true;
    return Continue;
}

ScriptRunner::Progress ScriptRunner::finished(const State& s) const {
    if (!bandFrameMs_.empty()) {  // how the UI kept up while images rendered in bands
        std::vector<double> t = bandFrameMs_;
        std::sort(t.begin(), t.end());
        std::printf("frames while rendering in bands: %zu, median %.1f ms, longest %.1f ms; the last image: %.1f ms\n",
                    t.size(), t[t.size() / 2], t.back(), s.renderMs);
        std::fflush(stdout);
    }
    return Done;
}

void ScriptRunner::noteFrame(const State& s) {
    const Clock::time_point now = Clock::now();
    if (s.tiling.active && lastFrame_ != Clock::time_point{})
        bandFrameMs_.push_back(std::chrono::duration<double, std::milli>(now - lastFrame_).count());
    lastFrame_ = now;
}

ScriptRunner::Progress ScriptRunner::rendering(State& s, const ViewerStep& st) {
    // Begun, with more than two bands still to do: a key in the next frame comes while it renders.
    if (s.tiling.active && s.tiling.done > 0 && s.tiling.height - s.tiling.done > 2 * s.tiling.rows) {
        ++next_;
        waitedFrames_ = 0;
        std::printf("rendering %dx%d in bands of %d rows\n", s.tiling.width, s.tiling.height, s.tiling.rows);
        std::fflush(stdout);
        return Continue;
    }
    if (++waitedFrames_ > 6000) failStep(st, "the viewer did not render an image in bands within 6000 frames");
    return Continue;
}

ScriptRunner::Progress ScriptRunner::press(State& s, GLFWwindow* window, const ViewerStep& st) {
    std::string keys;
    for (int i = 0; i < int(st.args.size()); ++i) {
        const int key = glfwKey(word(st, i));
        keyEvent(window, key, 0, GLFW_PRESS, 0);
        keyEvent(window, key, 0, GLFW_RELEASE, 0);
        keys += (keys.empty() ? "" : " ") + word(st, i);
    }
    std::vector<double> t = bandFrameMs_;  // the frames drawn while bands rendered, so far
    std::sort(t.begin(), t.end());
    if (s.tiling.active)
        std::printf("press %s: while rendering %dx%d, %d of %d rows done, frame %d of the image; frames while "
                    "rendering in bands so far: %zu, median %.1f ms, longest %.1f ms\n",
                    keys.c_str(), s.tiling.width, s.tiling.height, s.tiling.done, s.tiling.height, s.tiling.frames,
                    t.size(), t.empty() ? 0.0 : t[t.size() / 2], t.empty() ? 0.0 : t.back());
    else
        std::printf("press %s: %s\n", keys.c_str(), s.dirty || s.interactive ? "while the image refines" : "idle");
    std::fflush(stdout);
    return Continue;
}

ScriptRunner::Progress ScriptRunner::drag(State& s) {
    if (dragFrames_ > 0) {
        // The frame before this one rendered the previous drag step.
        if (s.interactive) dragTimes_.push_back(s.renderMs);
        char size[64];
        std::snprintf(size, sizeof size, "%dx%d", s.imageWidth, s.imageHeight);
        if (s.interactive) dragSize_ = size;
        if (s.interactive)
            dragLevel_ = s.coarseShown && s.coarseVolume
                             ? "level " + std::to_string(s.coarseLevel) + coarseFiltering(s.scene) : "";
        orbitCamera(&s.scene.camera, s.volume->extent(), dragDx_, dragDy_, s.fbWidth, s.fbHeight);
        s.lastInput = Clock::now();
        s.dirty = true;
        if (--dragFrames_ == 0) settling_ = true;
        return Continue;
    }
    // Settling: the viewer renders full quality once the mouse has rested.
    if (s.interactive) refinements_ = std::max(refinements_, s.refineStep);
    if (s.interactive || s.dirty || Clock::now() - s.lastInput < std::chrono::milliseconds(300)) return Continue;
    settling_ = false;
    std::vector<double> t = dragTimes_;
    std::sort(t.begin(), t.end());
    const double median = t.empty() ? 0.0 : t[t.size() / 2];
    char moving[64];
    if (dragLevel_.empty()) std::snprintf(moving, sizeof moving, "step %g", std::min(kMaxStep, s.scene.step * 2.0));
    else std::snprintf(moving, sizeof moving, "%s, step %g", dragLevel_.c_str(), std::min(kMaxStep, s.scene.step * 2.0));
    std::printf("drag: %zu frames, the last at %s, %s: median render %.1f ms (%.1f frames/s); "
                "idle, full quality %dx%d, step %g: %.1f ms, after %d refinement step%s\n",
                t.size(), dragSize_.c_str(), moving, median,
                median > 0 ? 1000.0 / median : 0.0, s.imageWidth, s.imageHeight, s.scene.step, s.renderMs,
                refinements_ + 1, refinements_ == 0 ? "" : "s");
    std::fflush(stdout);
    return Continue;
}

}  // namespace voxlab::viewer
