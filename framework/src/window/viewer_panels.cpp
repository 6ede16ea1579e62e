// voxlab viewer: the ImGui panels (technique, parameters, transfer
// functions, slices, ray profile); the overlays are in viewer_overlays.cpp.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cfloat>
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
#include "voxlab/stage_registry.h"

namespace voxlab::viewer {

namespace {

// A titled separator (ImGui 1.89's SeparatorText; Debian 12 has 1.86).
void sectionTitle(const char* title) {
    ImGui::Spacing();
    ImGui::TextDisabled("%s", title);
    ImGui::Separator();
}

// One widget per declared parameter: the panel is generated, never hand-made.
// Each row is the parameter's name in words on the left and its widget
// filling the rest, so that no label is cut off at any UI scale.
bool parameterWidgets(const Renderer& renderer, const Volume& volume, ParameterValues* values) {
    const std::vector<ParameterSpec> specs = renderer.parametersFor(volume.valueRange());
    if (specs.empty() || !ImGui::BeginTable("parameters", 2, ImGuiTableFlags_SizingFixedFit)) return false;
    ImGui::TableSetupColumn("name", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch);
    bool changed = false;
    for (const ParameterSpec& p : specs) {
        ImGui::PushID(p.name.c_str());
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::AlignTextToFramePadding();
        ImGui::TextUnformatted(parameterLabel(p.name).c_str());
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s)", p.description.c_str(), p.name.c_str());
        ImGui::TableNextColumn();
        ImGui::SetNextItemWidth(-FLT_MIN);
        double& value = values->try_emplace(p.name, p.defaultValue).first->second;
        if (p.type == ParameterType::Bool) {
            bool b = value != 0.0;
            if (ImGui::Checkbox("##v", &b)) value = b, changed = true;
        } else if (p.type == ParameterType::Int) {
            int i = int(value);
            if (ImGui::SliderInt("##v", &i, int(p.minValue), int(p.maxValue))) value = i, changed = true;
        } else {
            float f = float(value);
            const double limit = p.scaledByData() ? 1e30 : 512.0;
            const float lo = float(std::max(p.minValue, -limit)), hi = float(std::min(p.maxValue, limit));
            if (ImGui::SliderFloat("##v", &f, lo, hi)) value = f, changed = true;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s)", p.description.c_str(), p.name.c_str());
        ImGui::PopID();
    }
    ImGui::EndTable();
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

namespace {

// The technique panel's sections (techniquePanel, below).
void samplingSection(State& s, const Volume& volume) {
    sectionTitle("sampling");
    float step = float(s.scene.step);
    if (ImGui::SliderFloat("step", &step, 0.05f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
        s.scene.step = step, s.dirty = true;
    int interp = int(s.scene.interpolation);
    if (ImGui::Combo("interpolation", &interp, "nearest\0trilinear\0hardware\0cubic B-spline\0Catmull-Rom\0"))
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
    if (s.coarseLevel > 0) {
        ImGui::Checkbox("coarse level while moving", &s.coarseWhileMoving);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("While the view moves, draw the volume's level %d (each level halves every side,\n"
                              "a mean of 2x2x2 voxels) at up to the window's size; off: the volume itself\n"
                              "at a reduced size and twice the step.",
                              s.coarseLevel);
    }
    glm::dvec2 w = s.scene.window.value_or(volume.valueRange());
    float lo = float(w.x), hi = float(w.y);
    const float speed = float((volume.maxValue() - volume.minValue()) / 500.0 + 1e-6);
    if (ImGui::DragFloatRange2("window", &lo, &hi, speed, float(volume.minValue()), float(volume.maxValue())) &&
        hi > lo)
        s.scene.window = glm::dvec2(lo, hi), s.dirty = true;

}

void cameraSection(State& s) {
    sectionTitle("camera");
    int proj = s.scene.camera.projection == Projection::Orthographic ? 0 : 1;
    if (ImGui::Combo("projection", &proj, "orthographic\0perspective\0"))
        s.scene.camera.projection = proj == 0 ? Projection::Orthographic : Projection::Perspective, s.dirty = true;
    for (const char* v : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
        if (ImGui::SmallButton(v)) s.scene.camera.view = v, s.dirty = true;
        ImGui::SameLine();
    }
    if (ImGui::SmallButton("reset")) s.scene.camera = CameraSpec(), s.dirty = true;

}

void splitSection(State& s) {
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

}

void panelsSection(State& s) {
    sectionTitle("panels");
    ImGui::Checkbox("transfer function", &s.showTransferFunction);
    ImGui::SameLine();
    ImGui::Checkbox("slices", &s.showSlices);
    ImGui::SameLine();
    ImGui::Checkbox("ray profile", &s.showProfile);
    if (ImGui::Button("reload shaders (R)")) reloadShaders(s);
    ImGui::SameLine();
    if (ImGui::Button("screenshot (P)")) s.screenshotRequest = timestampedScreenshotName(), s.screenshotByKey = true;
    ImGui::SameLine();
    if (ImGui::Button("help (H)")) s.showHelp = !s.showHelp;

}

// The scene file: its name, save (atomically) and open.
void sceneFileSection(State& s) {
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

}  // namespace

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

    samplingSection(s, volume);
    cameraSection(s);
    if (sceneVolumeSections(s)) s.dirty = true;
    splitSection(s);
    panelsSection(s);
    sceneFileSection(s);
}

// What the 2D editor starts from: the dataset's preset (datasets/NAME/, NAME
// kTransferFunction2DName),
// else one triangle at the middle of the window.
TransferFunction2D startingTransferFunction2D(const State& s) {
    const std::string stem = std::filesystem::path(s.volume->name()).stem().string();
    try {
        return TransferFunction2D::load(resolveDataPath(std::string(kTransferFunction2DName) + "/" + stem + ".json"));
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
    const float scale = s.contentScale;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const Renderer* renderer = rendererRegistry().find(s.scene.renderer);
    // Beside the control panel, at the bottom: the two never overlap. With
    // no function in use the panel is only its checkbox and files, and
    // shrinks to them; it takes the editor's size again when one is used.
    const bool compact = !s.scene.transferFunction && !(renderer && renderer->needsTransferFunction2D());
    const float x = (s.showPanel ? s.panelRight : 0.0f) + 10 * scale;
    const ImGuiCond cond = s.relayout || compact != s.tfPanelCompact ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    s.tfPanelCompact = compact;
    const float width = std::min(460 * scale, std::max(200.0f, display.x - x - 10 * scale));
    ImGui::SetNextWindowPos(ImVec2(x, display.y - (compact ? 150 : 330) * scale), cond);
    ImGui::SetNextWindowSize(ImVec2(width, compact ? 0.0f : 320 * scale), cond);
    if (!ImGui::Begin("transfer function", &s.showTransferFunction, compact ? ImGuiWindowFlags_AlwaysAutoResize : 0))
        return ImGui::End();
    if (renderer && renderer->needsTransferFunction2D()) {  // asked of the renderer, not its name
        if (!s.histogram2D) s.histogram2D = histogram2D(volume);
        if (!s.scene.transferFunction2D) s.scene.transferFunction2D = startingTransferFunction2D(s);
        if (TransferFunction2DEditor("##2d", &*s.scene.transferFunction2D, *s.histogram2D, &s.selectedWidget))
            s.dirty = true;
        return ImGui::End();
    }
    // A label's own function, when the labels section chose one.
    if (s.scene.labels && s.editedLabel >= 0) {
        for (LabelClass& c : s.scene.labels->classes)
            if (c.label == s.editedLabel && c.transferFunction) {
                ImGui::Text("label %d%s%s", c.label, c.name.empty() ? "" : ": ", c.name.c_str());
                if (!s.histogram) s.histogram = volume.histogram();
                TransferFunctionEditorOptions options;
                options.histogram = &*s.histogram;
                options.range = volume.valueRange();
                if (TransferFunctionEditor("##labeltf", &*c.transferFunction, options, &s.selectedPoint)) s.dirty = true;
                return ImGui::End();
            }
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

std::string parameterLabel(const std::string& name) {
    std::string label = name;
    for (char& c : label)
        if (c == '_') c = ' ';
    return label;
}

void drawPanels(State& s) {
    const float scale = s.contentScale;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const ImGuiCond cond = s.relayout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    if (s.showPanel) {
        ImGui::SetNextWindowPos(ImVec2(10 * scale, 10 * scale), cond);
        ImGui::SetNextWindowSize(ImVec2(360 * scale, 0), cond);
        ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(FLT_MAX, std::max(100.0f, display.y - 20 * scale)));
        if (ImGui::Begin("voxlab", &s.showPanel)) techniquePanel(s);
        s.panelRight = ImGui::GetWindowPos().x + ImGui::GetWindowSize().x;
        ImGui::End();
    }
    // The transfer-function editor, only for a renderer that has one.
    const Renderer* renderer = rendererRegistry().find(s.scene.renderer);
    const bool hasTransferFunction =
        renderer && (renderer->usesTransferFunction() || renderer->needsTransferFunction2D());
    if (s.showTransferFunction && hasTransferFunction) transferFunctionPanel(s);
    if (s.showSlices) {
        if (!s.sliceViewer) s.sliceViewer = std::make_unique<SliceViewer>();
        ImGui::SetNextWindowPos(ImVec2(display.x - 430 * scale, 10 * scale), cond);
        ImGui::SetNextWindowSize(ImVec2(420 * scale, 470 * scale), cond);
        s.sliceViewer->draw("slices", *s.volume, &s.slices, &s.showSlices);
    }
    if (s.showProfile) {
        ImGui::SetNextWindowPos(ImVec2(display.x - 530 * scale, display.y - 360 * scale), cond);
        ImGui::SetNextWindowSize(ImVec2(520 * scale, 320 * scale), cond);
        if (ImGui::Begin("ray profile", &s.showProfile)) {
            if (s.profile) RayProfilePanel("##profile", *s.profile, s.scene.window.value_or(s.volume->valueRange()));
            else ImGui::TextDisabled("click a pixel of the image to follow its ray");
        }
        ImGui::End();
    }
}

}  // namespace voxlab::viewer
