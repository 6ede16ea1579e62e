// voxlab: GLFW windows (see window.h).
#define GLFW_INCLUDE_NONE
#include "voxlab/window.h"

#include <GLFW/glfw3.h>

#include <string>

#include "voxlab/error.h"

namespace voxlab {
namespace {

std::string lastGlfwError() {
    const char* text = nullptr;
#ifndef __EMSCRIPTEN__  // emscripten's GLFW (3.2) has no glfwGetError
    glfwGetError(&text);
#endif
    return text ? text : "unknown GLFW error";
}

}  // namespace

GlfwWindow::GlfwWindow(int width, int height, const std::string& title, bool visible) {
    if (!glfwInit()) throw Error("cannot open a window: " + lastGlfwError());
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
#ifdef __APPLE__
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);  // required on macOS (lines stay 1 pixel wide there)
#else
    // Not forward-compatible elsewhere: wide lines (the wireframes at the UI's scale) stay allowed.
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_FALSE);
#endif
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
#ifdef GLFW_SCALE_TO_MONITOR                                // (GLFW 3.3; not emscripten's)
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);       // high-DPI screens
#endif
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        const std::string why = lastGlfwError();
        glfwTerminate();
        throw Error("cannot open an OpenGL 3.3 core window: " + why);
    }
    makeCurrent();
    loadFunctions("GLFW");
}

GlfwWindow::~GlfwWindow() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

void GlfwWindow::makeCurrent() { glfwMakeContextCurrent(window_); }

GlProc GlfwWindow::getProcAddress(const char* name) const { return glfwGetProcAddress(name); }

}  // namespace voxlab
