// voxlab: a GLFW window with an OpenGL 3.3 core context, as a GlContext.
#pragma once

#include <string>

#include "voxlab/gl_context.h"

struct GLFWwindow;

namespace voxlab {

class GlfwWindow final : public GlContext {
public:
    // Throws voxlab::Error when there is no display or no 3.3 core context.
    GlfwWindow(int width, int height, const std::string& title, bool visible = true);
    ~GlfwWindow() override;
    void makeCurrent() override;
    GlProc getProcAddress(const char* name) const override;
    GLFWwindow* handle() const { return window_; }

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace voxlab
