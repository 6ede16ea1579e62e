// voxlab: the interactive viewer. Left-drag orbits, scroll zooms, the panel
// switches renderers and edits every declared parameter, R reloads shaders.
#include "voxlab_gl.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "voxlab/error.h"
#include "voxlab/render_engine.h"
#include "voxlab/viewer.h"
#include "voxlab/window.h"

namespace voxlab {
namespace {

struct ViewerState {
    Scene scene;
    bool dirty = true;
    std::string error;       // last render or shader error, shown in an overlay
    double renderMs = 0.0;
    bool dragging = false;
    double lastX = 0, lastY = 0;
};

void drawPanel(ViewerState& s, RenderEngine& engine, const Volume& volume) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("voxlab");
    const glm::ivec3 d = volume.dims();
    ImGui::Text("%s  %dx%dx%d %s", volume.name().c_str(), d.x, d.y, d.z, voxelTypeName(volume.type()));
    ImGui::Text("values %g .. %g", volume.minValue(), volume.maxValue());
    ImGui::Separator();

    if (ImGui::BeginCombo("renderer", s.scene.renderer.c_str())) {
        for (const auto& r : rendererRegistry().all()) {
            if (ImGui::Selectable(r->id().c_str(), r->id() == s.scene.renderer)) {
                s.scene.renderer = r->id();
                s.scene.parameters.clear();
                s.dirty = true;
            }
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", r->description().c_str());
        }
        ImGui::EndCombo();
    }
    // One widget per declared parameter: the panel is generated, never hand-made.
    const Renderer& renderer = rendererRegistry().get(s.scene.renderer);
    for (const ParameterSpec& p : renderer.parametersFor(volume.valueRange())) {
        ImGui::PushID(p.name.c_str());
        double& value = s.scene.parameters.try_emplace(p.name, p.defaultValue).first->second;
        if (p.type == ParameterType::Bool) {
            bool b = value != 0.0;
            if (ImGui::Checkbox(p.name.c_str(), &b)) value = b, s.dirty = true;
        } else if (p.type == ParameterType::Int) {
            int i = int(value);
            if (ImGui::SliderInt(p.name.c_str(), &i, int(p.minValue), int(p.maxValue))) value = i, s.dirty = true;
        } else {
            float f = float(value);
            const double limit = p.dataUnits ? 1e30 : 512.0;
            const float lo = float(std::max(p.minValue, -limit)), hi = float(std::min(p.maxValue, limit));
            if (ImGui::SliderFloat(p.name.c_str(), &f, lo, hi)) value = f, s.dirty = true;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
        ImGui::PopID();
    }
    ImGui::Separator();

    float step = float(s.scene.step);
    if (ImGui::SliderFloat("step", &step, 0.05f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
        s.scene.step = step, s.dirty = true;
    int interp = int(s.scene.interpolation);
    if (ImGui::Combo("interpolation", &interp, "nearest\0trilinear\0hardware\0"))
        s.scene.interpolation = Interpolation(interp), s.dirty = true;
    int proj = s.scene.camera.projection == Projection::Orthographic ? 0 : 1;
    if (ImGui::Combo("projection", &proj, "orthographic\0perspective\0"))
        s.scene.camera.projection = proj == 0 ? Projection::Orthographic : Projection::Perspective, s.dirty = true;

    glm::dvec2 w = s.scene.window.value_or(volume.valueRange());
    float lo = float(w.x), hi = float(w.y);
    const float speed = float((volume.maxValue() - volume.minValue()) / 500.0 + 1e-6);
    if (ImGui::DragFloatRange2("window", &lo, &hi, speed, float(volume.minValue()), float(volume.maxValue()))) {
        if (hi > lo) s.scene.window = glm::dvec2(lo, hi), s.dirty = true;
    }
    bool useTf = s.scene.transferFunction.has_value();
    if (ImGui::Checkbox("transfer function", &useTf)) {
        s.scene.transferFunction.reset();
        if (useTf) s.scene.transferFunction = TransferFunction::ramp(w.x, w.y);
        s.dirty = true;
    }

    ImGui::Text("view");
    for (const char* v : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
        ImGui::SameLine();
        if (ImGui::SmallButton(v)) s.scene.camera.view = v, s.dirty = true;
    }
    if (ImGui::Button("reload shaders (R)")) engine.reloadShaders(), s.dirty = true;
    ImGui::Text("render %.1f ms at %dx%d", s.renderMs, s.scene.width, s.scene.height);
    ImGui::TextDisabled("drag: orbit   scroll: zoom   1-9: renderer");
    ImGui::End();

    if (!s.error.empty()) {
        ImGui::SetNextWindowPos(ImVec2(360, 10), ImGuiCond_Always);
        ImGui::Begin("error", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
        ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "%s", s.error.c_str());
        ImGui::End();
    }
}

void handleInput(GLFWwindow* window, ViewerState& s, RenderEngine& engine) {
    ImGuiIO& io = ImGui::GetIO();
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    const bool down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    if (down && !s.dragging && !io.WantCaptureMouse) s.dragging = true;
    if (!down) s.dragging = false;
    if (s.dragging && (x != s.lastX || y != s.lastY)) {
        CameraSpec& c = s.scene.camera;
        if (!c.view.empty()) axisViewOrbitAngles(c.view, &c.azimuth, &c.elevation), c.view.clear();
        c.azimuth += 0.4 * (x - s.lastX);
        // No clamp: the orbit passes smoothly over the poles (the image's up
        // direction turns with it), so elevation just wraps to (-180, 180].
        c.elevation = std::remainder(c.elevation + 0.4 * (y - s.lastY), 360.0);
        s.dirty = true;
    }
    s.lastX = x, s.lastY = y;
    if (io.MouseWheel != 0.0f && !io.WantCaptureMouse) {
        s.scene.camera.zoom *= std::pow(1.1, io.MouseWheel);
        s.dirty = true;
    }
    if (!io.WantCaptureKeyboard) {
        if (ImGui::IsKeyPressed(GLFW_KEY_R, false)) engine.reloadShaders(), s.dirty = true;
        const auto& all = rendererRegistry().all();
        for (int k = 0; k < 9 && k < int(all.size()); ++k)
            if (ImGui::IsKeyPressed(GLFW_KEY_1 + k, false))
                s.scene.renderer = all[k]->id(), s.scene.parameters.clear(), s.dirty = true;
    }
}

void saveWindowScreenshot(int width, int height, const std::string& path) {
    Image img(width, height);
    std::vector<unsigned char> rows(std::size_t(width) * height * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    for (int yy = 0; yy < height; ++yy)
        for (int xx = 0; xx < width; ++xx) {
            const unsigned char* p = &rows[(std::size_t(height - 1 - yy) * width + xx) * 4];
            img.set(xx, yy, glm::vec4(p[0], p[1], p[2], 255) / 255.0f);
        }
    savePng(img, path);
}

}  // namespace

int runViewer(const Scene& initial, const ViewerOptions& options) {
    const Volume volume = loadVolume(initial.dataset);
    GlfwWindow window(options.width, options.height, "voxlab - " + volume.name());
    RenderEngine engine(options.implementationRoot);
    engine.setVolume(volume);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini litter in the working folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window.handle(), true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    ViewerState s;
    s.scene = initial;
    glfwSwapInterval(1);
    int frame = 0;
    while (!glfwWindowShouldClose(window.handle())) {
        glfwPollEvents();
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        handleInput(window.handle(), s, engine);
        drawPanel(s, engine, volume);

        int fbw, fbh;
        glfwGetFramebufferSize(window.handle(), &fbw, &fbh);
        if (fbw != s.scene.width || fbh != s.scene.height) s.scene.width = fbw, s.scene.height = fbh, s.dirty = true;
        if (s.dirty && fbw > 0 && fbh > 0) {
            const auto t0 = std::chrono::steady_clock::now();
            try {
                engine.renderOffscreen(s.scene);
                glFinish();
                s.error.clear();
            } catch (const Error& e) {
                s.error = e.what();  // keep showing the last good image
            }
            s.renderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            s.dirty = false;
        }
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glViewport(0, 0, fbw, fbh);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        if (engine.offscreenFramebuffer()) {
            glBindFramebuffer(GL_READ_FRAMEBUFFER, engine.offscreenFramebuffer());
            glBlitFramebuffer(0, 0, s.scene.width, s.scene.height, 0, 0, fbw, fbh, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        }
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        ++frame;
        if (!options.screenshot.empty() && frame >= std::max(options.frames, 2)) {
            saveWindowScreenshot(fbw, fbh, options.screenshot);
            std::printf("%s\n", options.screenshot.c_str());
            break;
        }
        glfwSwapBuffers(window.handle());
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return 0;
}

}  // namespace voxlab
