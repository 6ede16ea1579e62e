// voxlab viewer: the ImGui panels (technique, parameters, transfer
// functions, slices, ray profile) and the overlays (frame time, errors,
// help, the split view's divider).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "transfer_function_editor_drawing.h"  // inputText for std::string
#include "viewer_state.h"
#include "voxlab/atomic_file.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/ray_profile_panel.h"
#include "voxlab/renderer.h"

namespace voxlab::viewer {

namespace {

// A titled separator (ImGui 1.89's SeparatorText; Debian 12 has 1.86).
void sectionTitle(const char* title) {
    ImGui::Spacing();
    ImGui::TextDisabled("%s", title);
    ImGui::Separator();
}

// One widget per declared parameter: the panel is generated, never hand-made.
bool parameterWidgets(const Renderer& renderer, const Volume& volume, ParameterValues* values) {
    bool changed = false;
    for (const ParameterSpec& p : renderer.parametersFor(volume.valueRange())) {
        ImGui::PushID(p.name.c_str());
        double& value = values->try_emplace(p.name, p.defaultValue).first->second;
        if (p.type == ParameterType::Bool) {
            bool b = value != 0.0;
            if (ImGui::Checkbox(p.name.c_str(), &b)) value = b, changed = true;
        } else if (p.type == ParameterType::Int) {
            int i = int(value);
            if (ImGui::SliderInt(p.name.c_str(), &i, int(p.minValue), int(p.maxValue))) value = i, changed = true;
        } else {
            float f = float(value);
            const double limit = p.dataUnits ? 1e30 : 512.0;
            const float lo = float(std::max(p.minValue, -limit)), hi = float(std::min(p.maxValue, limit));
            if (ImGui::SliderFloat(p.name.c_str(), &f, lo, hi)) value = f, changed = true;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
        ImGui::PopID();
    }
    return changed;
}

bool rendererCombo(const char* label, std::string* id, bool allowSame) {
    bool changed = false;
    const std::string shown = id->empty() ? "(same as left)" : *id;
    if (ImGui::BeginCombo(label, shown.c_str())) {
        if (allowSame && ImGui::Selectable("(same as left)", id->empty())) *id = "", changed = true;
        int k = 1;
        for (const auto& r : rendererRegistry().all()) {
            if (ImGui::Selectable(r->id().c_str(), r->id() == *id)) *id = r->id(), changed = true;
            if (k <= 9) {
                ImGui::SameLine(ImGui::GetContentRegionAvail().x - 10);
                ImGui::TextDisabled("%d", k);
            }
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", r->description().c_str());
            ++k;
        }
        ImGui::EndCombo();
    }
    return changed;
}

// The implementation switch: reference | student (and the folder the
// student side reads).
void implementationSwitch(const char* label, State& s, Side& side) {
    int which = side.implementation.empty() ? 0 : 1;
    if (!s.hasReference) {  // a student release: the starter code is the only implementation
        ImGui::Text("%s your code (assignments/)", label);
        return;
    }
    ImGui::PushID(label);
    ImGui::TextUnformatted(label);
    ImGui::SameLine();
    bool changed = ImGui::RadioButton("reference", &which, 0);
    ImGui::SameLine();
    changed |= ImGui::RadioButton("student", &which, 1);
    if (changed) {
        try {
            setImplementation(side, which == 0 ? "" : s.studentRoot, *s.volume);
            s.dirty = true;
        } catch (const Error& e) {
            s.say(e.what());
        }
    }
    ImGui::PopID();
}

void techniquePanel(State& s) {
    const Volume& volume = *s.volume;
    const glm::ivec3 d = volume.dims();
    ImGui::Text("%s  %dx%dx%d %s", volume.name().c_str(), d.x, d.y, d.z, voxelTypeName(volume.type()));
    ImGui::TextDisabled("values %g .. %g   spacing %g %g %g", volume.minValue(), volume.maxValue(),
                        volume.spacing().x, volume.spacing().y, volume.spacing().z);
    sectionTitle("technique");
    if (rendererCombo("renderer", &s.scene.renderer, false)) s.scene.parameters.clear(), s.dirty = true;
    if (parameterWidgets(rendererRegistry().get(s.scene.renderer), volume, &s.scene.parameters)) s.dirty = true;
    implementationSwitch("left:", s, s.main);

    sectionTitle("sampling");
    float step = float(s.scene.step);
    if (ImGui::SliderFloat("step", &step, 0.05f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
        s.scene.step = step, s.dirty = true;
    int interp = int(s.scene.interpolation);
    if (ImGui::Combo("interpolation", &interp, "nearest\0trilinear\0hardware\0"))
        s.scene.interpolation = Interpolation(interp), s.dirty = true;
    if (ImGui::Checkbox("skip empty space", &s.scene.skipEmptySpace)) s.dirty = true;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Leap over bricks the transfer function hides (same image, fewer samples;\n"
                          "see docs/performance.md). Turn off to compare frame times.");
    ImGui::SameLine();
    if (ImGui::Checkbox("show samples", &s.showSamples)) s.dirty = true;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Colour each pixel by the samples its ray takes (black: none; yellow: a ray\n"
                          "along the box's diagonal with no skipping). Ray casters without a cutting plane.");
    glm::dvec2 w = s.scene.window.value_or(volume.valueRange());
    float lo = float(w.x), hi = float(w.y);
    const float speed = float((volume.maxValue() - volume.minValue()) / 500.0 + 1e-6);
    if (ImGui::DragFloatRange2("window", &lo, &hi, speed, float(volume.minValue()), float(volume.maxValue())) &&
        hi > lo)
        s.scene.window = glm::dvec2(lo, hi), s.dirty = true;

    sectionTitle("camera");
    int proj = s.scene.camera.projection == Projection::Orthographic ? 0 : 1;
    if (ImGui::Combo("projection", &proj, "orthographic\0perspective\0"))
        s.scene.camera.projection = proj == 0 ? Projection::Orthographic : Projection::Perspective, s.dirty = true;
    for (const char* v : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
        if (ImGui::SmallButton(v)) s.scene.camera.view = v, s.dirty = true;
        ImGui::SameLine();
    }
    if (ImGui::SmallButton("reset")) s.scene.camera = CameraSpec(), s.dirty = true;

    sectionTitle("split view (S)");
    int split = int(s.split);
    const char* modes = s.hasReference ? "off\0student | reference\0difference\0"
                                       : "off\0yours | expected image\0difference\0";
    if (ImGui::Combo("mode", &split, modes)) s.split = SplitMode(split), s.dirty = true;
    if (comparesWithExpected(s)) {
        ImGui::TextWrapped("%s", s.expected.available ? ("the grading scene as graded, against " +
                                                         s.expected.path.substr(projectRoot().size() + 1))
                                                            .c_str()
                                                      : s.expected.why.c_str());
    } else if (s.split != SplitMode::Off) {
        if (rendererCombo("right renderer", &s.other.renderer, true)) s.dirty = true;
        if (s.other.engine) implementationSwitch("right:", s, s.other);
    }

    sectionTitle("panels");
    ImGui::Checkbox("transfer function", &s.showTransferFunction);
    ImGui::SameLine();
    ImGui::Checkbox("slices", &s.showSlices);
    ImGui::SameLine();
    ImGui::Checkbox("ray profile", &s.showProfile);
    if (ImGui::Button("reload shaders (R)")) {
        s.main.engine->reloadShaders();
        if (s.other.engine) s.other.engine->reloadShaders();
        s.dirty = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("screenshot (P)")) s.screenshotRequest = timestampedScreenshotName();
    ImGui::SameLine();
    if (ImGui::Button("help (H)")) s.showHelp = !s.showHelp;

    if (s.scenePathField.empty()) s.scenePathField = s.scenePath;
    tf_editor::inputText("##scenepath", &s.scenePathField);
    ImGui::SameLine();
    if (ImGui::Button("save scene")) {
        const std::string path = s.scenePathField;
        try {
            if (path.empty()) throw Error("save scene: no file name given");
            writeFileAtomically(path, s.scene.toJson().dump(2) + "\n");  // the old scene survives a failure
            s.scenePath = path;
            s.say("saved " + path);
        } catch (const std::exception& e) {
            s.say(e.what());
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("open")) s.dropped.push_back(s.scenePathField);
}

// What the 2D editor starts from: the dataset's preset (datasets/tf2d/),
// else one triangle at the middle of the window.
TransferFunction2D startingTransferFunction2D(const State& s) {
    const std::string stem = std::filesystem::path(s.volume->name()).stem().string();
    try {
        return TransferFunction2D::load(resolveDataPath("tf2d/" + stem + ".json"));
    } catch (const Error&) {
    }
    const glm::dvec2 w = s.scene.window.value_or(s.volume->valueRange());
    Tf2dWidget triangle;
    triangle.valueRange = glm::dvec2(0.5 * (w.x + w.y));
    triangle.radius = 1.5;
    triangle.alpha = 0.6f;
    return TransferFunction2D({triangle});
}

void transferFunctionPanel(State& s) {
    const Volume& volume = *s.volume;
    ImGui::SetNextWindowPos(ImVec2(10 * s.contentScale, float(s.fbHeight) - 330 * s.contentScale),
                            ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(460 * s.contentScale, 320 * s.contentScale), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("transfer function", &s.showTransferFunction)) return ImGui::End();
    const Renderer* renderer = rendererRegistry().find(s.scene.renderer);
    if (renderer && renderer->needsTransferFunction2D()) {  // asked of the renderer, not its name
        if (!s.histogram2D) s.histogram2D = histogram2D(volume);
        if (!s.scene.transferFunction2D) s.scene.transferFunction2D = startingTransferFunction2D(s);
        if (TransferFunction2DEditor("##tf2d", &*s.scene.transferFunction2D, *s.histogram2D, &s.selectedWidget))
            s.dirty = true;
        return ImGui::End();
    }
    bool use = s.scene.transferFunction.has_value();
    if (ImGui::Checkbox("use a transfer function", &use)) {
        if (use) s.scene.transferFunction = TransferFunction::ramp(volume.minValue(), volume.maxValue());
        else s.scene.transferFunction.reset();
        s.dirty = true;
    }
    if (s.scene.transferFunction) {
        if (!s.histogram) s.histogram = volume.histogram();
        TransferFunctionEditorOptions options;
        options.histogram = &*s.histogram;
        options.range = volume.valueRange();
        if (TransferFunctionEditor("##tf", &*s.scene.transferFunction, options, &s.selectedPoint)) s.dirty = true;
        if (TransferFunctionUndoRedo(&s.history, &*s.scene.transferFunction)) s.dirty = true;
    }
    TransferFunction edited = s.scene.transferFunction.value_or(TransferFunction::ramp(volume.minValue(), volume.maxValue()));
    if (TransferFunctionFiles("files", &edited, volume.name(), &s.tfPath, &s.tfMessage)) {
        s.scene.transferFunction = edited;
        s.dirty = true;
    }
    ImGui::End();
}

}  // namespace

void drawPanels(State& s) {
    const float scale = s.contentScale;
    if (s.showPanel) {
        ImGui::SetNextWindowPos(ImVec2(10 * scale, 10 * scale), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(360 * scale, 0), ImGuiCond_FirstUseEver);
        if (ImGui::Begin("voxlab", &s.showPanel)) techniquePanel(s);
        ImGui::End();
    }
    if (s.showTransferFunction) transferFunctionPanel(s);
    if (s.showSlices) {
        if (!s.sliceViewer) s.sliceViewer = std::make_unique<SliceViewer>();
        ImGui::SetNextWindowPos(ImVec2(float(s.fbWidth) - 430 * scale, 10 * scale), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(420 * scale, 470 * scale), ImGuiCond_FirstUseEver);
        s.sliceViewer->draw("slices", *s.volume, &s.slices, &s.showSlices);
    }
    if (s.showProfile) {
        ImGui::SetNextWindowPos(ImVec2(float(s.fbWidth) - 530 * scale, float(s.fbHeight) - 360 * scale),
                                ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(520 * scale, 320 * scale), ImGuiCond_FirstUseEver);
        if (ImGui::Begin("ray profile", &s.showProfile)) {
            if (s.profile) RayProfilePanel("##profile", *s.profile, s.scene.window.value_or(s.volume->valueRange()));
            else ImGui::TextDisabled("click a pixel of the image to follow its ray");
        }
        ImGui::End();
    }
}

void drawOverlays(State& s) {
    ImDrawList* fg = ImGui::GetForegroundDrawList();
    ImDrawList* bg = ImGui::GetBackgroundDrawList();
    const ImGuiIO& io = ImGui::GetIO();
    const ImVec2 size = io.DisplaySize;
    const float scale = s.contentScale;

    // The slice planes in the 3D view.
    if (s.showSlices && s.volume) {
        const Camera camera = Camera::make(s.scene.camera, s.volume->extent(), s.fbWidth, s.fbHeight);
        drawSlicePlanes(bg, camera, s.volume->extent(), s.volume->spacing(), s.slices.voxel, ImVec2(0, 0), size);
    }
    // The split view's divider and labels.
    if (s.split == SplitMode::Split) {
        const float x = s.divider * size.x;
        fg->AddLine(ImVec2(x, 0), ImVec2(x, size.y), IM_COL32(255, 255, 255, 200), 2.0f * scale);
        fg->AddCircleFilled(ImVec2(x, size.y * 0.5f), 7.0f * scale, IM_COL32(255, 255, 255, 230));
        auto label = [&](const Side& side, bool right) {
            std::string text = (side.renderer.empty() ? s.scene.renderer : side.renderer) + " · " +
                               (side.implementation.empty() ? "reference" : "student");
            if (comparesWithExpected(s))  // a student release: never "reference"
                text = right ? (s.expected.available ? "expected: " + std::filesystem::path(s.expected.path).filename().string()
                                                     : std::string("expected: none"))
                             : "yours: " + s.expected.scene.renderer;
            const ImVec2 t = ImGui::CalcTextSize(text.c_str());
            const float lx = right ? x + 12 * scale : x - 12 * scale - t.x;
            fg->AddRectFilled(ImVec2(lx - 6, size.y - 34 * scale), ImVec2(lx + t.x + 6, size.y - 34 * scale + t.y + 6),
                              IM_COL32(0, 0, 0, 160), 4.0f);
            fg->AddText(ImVec2(lx, size.y - 31 * scale), IM_COL32(255, 255, 255, 255), text.c_str());
        };
        label(s.main, false);
        label(s.other, true);
    } else if (s.split == SplitMode::Difference) {
        fg->AddText(ImVec2(size.x * 0.5f - 120 * scale, size.y - 30 * scale), IM_COL32(255, 255, 255, 255),
                    "difference |left - right| x4 (black: equal)");
    }
    if (comparesWithExpected(s) && !s.expected.available) {  // a student release away from a grading scene
        const ImVec2 t = ImGui::CalcTextSize(s.expected.why.c_str());
        fg->AddRectFilled(ImVec2(size.x * 0.5f - t.x * 0.5f - 8, size.y * 0.5f - 8),
                          ImVec2(size.x * 0.5f + t.x * 0.5f + 8, size.y * 0.5f + t.y + 8), IM_COL32(0, 0, 0, 200), 4.0f);
        fg->AddText(ImVec2(size.x * 0.5f - t.x * 0.5f, size.y * 0.5f), IM_COL32(255, 220, 120, 255),
                    s.expected.why.c_str());
    }

    // Frame time, bottom right, always; in the samples view the samples too.
    char samples[128] = "";
    if (s.samplesShown && s.samplesFull > 0)
        std::snprintf(samples, sizeof samples, "  samples %.3g of %.3g (%.0f%% skipped)", s.samplesTaken,
                      s.samplesFull, 100.0 * std::max(0.0, 1.0 - s.samplesTaken / s.samplesFull));
    else if (s.showSamples)
        std::snprintf(samples, sizeof samples, "  samples: ray casters without a cutting plane only");
    char line[320];
    std::snprintf(line, sizeof line, "%s  render %.1f ms (%.1f frames/s)  %dx%d%s%s", s.scene.renderer.c_str(),
                  s.renderMs, s.renderMs > 0 ? 1000.0 / s.renderMs : 0.0, s.imageWidth, s.imageHeight,
                  s.interactive ? "  interactive: reduced size, double step" : "", samples);
    const ImVec2 t = ImGui::CalcTextSize(line);
    fg->AddRectFilled(ImVec2(size.x - t.x - 18 * scale, size.y - t.y - 14 * scale), ImVec2(size.x, size.y),
                      IM_COL32(0, 0, 0, 150));
    fg->AddText(ImVec2(size.x - t.x - 10 * scale, size.y - t.y - 8 * scale), IM_COL32(230, 230, 230, 255), line);

    // Errors: a side's render error, or a shader that no longer compiles
    // (the last good one keeps rendering).
    std::string errors;
    for (const Side* side : {&s.main, &s.other}) {
        if (!side->engine) continue;
        if (!side->error.empty()) errors += side->error + "\n";
        if (!side->engine->shaderError().empty())
            errors += side->engine->shaderError() + "\n(showing the last shader that compiled)\n";
    }
    if (!errors.empty()) {
        ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, 10 * scale), ImGuiCond_Always, ImVec2(0.5f, 0.0f));
        ImGui::SetNextWindowBgAlpha(0.85f);
        ImGui::Begin("shader error", nullptr,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings);
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", errors.c_str());
        ImGui::End();
    }
    if (!s.toast.empty() && Clock::now() < s.toastUntil) {
        const ImVec2 tt = ImGui::CalcTextSize(s.toast.c_str());
        const ImVec2 at(size.x * 0.5f - tt.x * 0.5f, size.y - 70 * scale);
        fg->AddRectFilled(ImVec2(at.x - 10, at.y - 6), ImVec2(at.x + tt.x + 10, at.y + tt.y + 6), IM_COL32(20, 20, 30, 220), 6);
        fg->AddText(at, IM_COL32(255, 255, 255, 255), s.toast.c_str());
    }
    if (s.showHelp) {
        ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
        ImGui::SetNextWindowBgAlpha(0.92f);
        ImGui::Begin("keys", &s.showHelp, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
        const char* keys[][2] = {{"left drag", "orbit"},
                                 {"right or middle drag, shift+drag", "pan"},
                                 {"wheel", "zoom"},
                                 {"click", "ray profile of that pixel (with the panel open)"},
                                 {"1 - 9", "switch technique"},
                                 {"S", "split view: off, student | reference, difference"},
                                 {"I", "left side: student / reference implementation"},
                                 {"R", "reload shaders (also automatic when a file is saved)"},
                                 {"X Y Z, shift for minus", "axis views"},
                                 {"O", "orthographic / perspective"},
                                 {"space", "reset the camera"},
                                 {"T  L  F", "transfer function, slices, ray profile panels"},
                                 {"Tab", "hide the control panel"},
                                 {"P", "screenshot (PNG in the working folder)"},
                                 {"ctrl+Z  ctrl+Y", "undo / redo transfer-function edits"},
                                 {"H", "this help"},
                                 {"drop a file", "open a dataset or a scene .json"}};
        if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg)) {
            for (const auto& k : keys) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextColored(ImVec4(1.0f, 0.85f, 0.4f, 1.0f), "%s", k[0]);
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(k[1]);
            }
            ImGui::EndTable();
        }
        ImGui::End();
    }
}

}  // namespace voxlab::viewer
