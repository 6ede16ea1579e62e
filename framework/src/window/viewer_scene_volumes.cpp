// voxlab viewer: the scene's other volumes and its clip planes: the label
// map's classes (show, hide, which function the editor edits, nearest or
// masks, the distance colouring), the fused second volume (mode, checker
// size, split plane) and the clip planes, in the control panel; and the clip
// planes drawn over the image, each as its outline on the box with a handle
// that drags it along its normal.
//
// Widgets follow Dear ImGui's habit: each returns true when it changed the
// scene, and the caller re-renders.
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include "transfer_function_editor_drawing.h"  // inputText for std::string
#include "viewer_state.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/label_map.h"

namespace voxlab::viewer {
namespace {

const ImU32 kPlaneColours[kMaxClipPlanes] = {IM_COL32(255, 200, 60, 255),  IM_COL32(80, 220, 255, 255),
                                             IM_COL32(255, 110, 200, 255), IM_COL32(140, 255, 120, 255),
                                             IM_COL32(255, 140, 80, 255),  IM_COL32(180, 160, 255, 255)};

// A transfer function over distances (world units) that starts the
// distance colouring: yellow and opaque at the structure, blue and faint
// 20 units away.
TransferFunction startingDistanceFunction() {
    return TransferFunction({{0.0, glm::vec3(1.0f, 0.9f, 0.1f), 1.0f}, {20.0, glm::vec3(0.1f, 0.3f, 1.0f), 0.1f}});
}

// The labels in the current label map and their voxel counts (read again
// only when the file changes).
const std::vector<std::uint64_t>& labelCounts(State& s) {
    if (s.labelCountsPath != s.scene.labels->volume) {
        s.labelCounts.clear();
        s.labelCountsPath = s.scene.labels->volume;
        try {
            s.labelCounts = voxlab::labelCounts(checkedLabels(loadVolume(s.scene.labels->volume), *s.volume));
        } catch (const Error& e) {
            s.say(e.what());
        }
    }
    return s.labelCounts;
}

LabelClass& classOf(LabelMap& map, int label) {
    for (LabelClass& c : map.classes)
        if (c.label == label) return c;
    map.classes.push_back(LabelClass{label, "", std::nullopt, true});
    return map.classes.back();
}

// A path field and a button that loads what it names; true when loaded.
bool pathLoader(const char* id, std::string* field, const char* button, std::string* resolved, State& s) {
    ImGui::PushID(id);
    ImGui::SetNextItemWidth(-ImGui::CalcTextSize(button).x - 2 * ImGui::GetStyle().FramePadding.x -
                            ImGui::GetStyle().ItemSpacing.x);
    tf_editor::inputText("##path", field);
    ImGui::SameLine();
    bool loaded = false;
    if (ImGui::Button(button)) {
        try {
            *resolved = resolveDataPath(*field);
            loaded = true;
        } catch (const Error& e) {
            s.say(e.what());
        }
    }
    ImGui::PopID();
    return loaded;
}

bool labelRows(State& s) {
    LabelMap& map = *s.scene.labels;
    const std::vector<std::uint64_t>& counts = labelCounts(s);
    bool changed = false;
    if (!ImGui::BeginTable("labels", 4, ImGuiTableFlags_SizingFixedFit)) return false;
    for (int label = 0; label < int(counts.size()); ++label) {
        if (counts[std::size_t(label)] == 0 && !map.find(label)) continue;
        ImGui::PushID(label);
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        const LabelClass* c = map.find(label);
        bool visible = !c || c->visible;
        if (ImGui::Checkbox("##visible", &visible)) classOf(map, label).visible = visible, changed = true;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("show or hide label %d", label);
        ImGui::TableNextColumn();
        const std::string name = c && !c->name.empty() ? c->name : label == 0 ? "no label" : "";
        ImGui::Text("%d %s", label, name.c_str());
        ImGui::TableNextColumn();
        ImGui::TextDisabled("%llu voxels", (unsigned long long)counts[std::size_t(label)]);
        ImGui::TableNextColumn();
        const bool own = c && c->transferFunction;
        if (ImGui::RadioButton(own ? "edit" : "edit (scene's)", s.editedLabel == label)) {
            LabelClass& edited = classOf(map, label);
            if (!edited.transferFunction)  // start from what it shows now
                edited.transferFunction = s.scene.transferFunction.value_or(
                    defaultCompositingFunction(s.scene.window.value_or(s.volume->valueRange())));
            s.editedLabel = label, changed = true;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("edit this label's transfer function in the editor");
        ImGui::PopID();
    }
    ImGui::EndTable();
    return changed;
}

bool labelSection(State& s) {
    if (!ImGui::CollapsingHeader("labels", s.scene.labels ? ImGuiTreeNodeFlags_DefaultOpen : 0)) return false;
    if (!s.scene.labels) {
        ImGui::TextDisabled("no label map: load one on this dataset's grid");
        std::string path;
        if (!pathLoader("labelmap", &s.labelPathField, "load", &path, s)) return false;
        s.scene.labels = LabelMap{path, LabelSampling::Nearest, {}, std::nullopt};
        return true;
    }
    LabelMap& map = *s.scene.labels;
    bool changed = false;
    int sampling = map.sampling == LabelSampling::Masks ? 1 : 0;
    if (ImGui::Combo("sampling##labels", &sampling, "nearest voxel\0blended masks\0"))
        map.sampling = sampling == 1 ? LabelSampling::Masks : LabelSampling::Nearest, changed = true;
    if (ImGui::RadioButton("edit the scene's function", s.editedLabel < 0)) s.editedLabel = -1, changed = true;
    changed |= labelRows(s);
    bool distance = map.distance.has_value();
    if (ImGui::Checkbox("colour by distance to label", &distance)) {
        if (distance) map.distance = LabelDistance{map.classes.empty() ? 1 : map.classes.back().label,
                                                   startingDistanceFunction(), {}};
        else map.distance.reset();
        changed = true;
    }
    if (map.distance) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(80 * s.contentScale);
        if (ImGui::InputInt("##to", &map.distance->to)) {
            map.distance->to = std::clamp(map.distance->to, 0, kMaxLabel);
            changed = true;
        }
    }
    if (ImGui::SmallButton("remove the label map")) s.scene.labels.reset(), s.editedLabel = -1, changed = true;
    return changed;
}

bool fusionSection(State& s) {
    if (!ImGui::CollapsingHeader("second volume (fusion)", s.scene.fusion ? ImGuiTreeNodeFlags_DefaultOpen : 0))
        return false;
    if (!s.scene.fusion) {
        ImGui::TextDisabled("no second volume: load one over the same box");
        std::string path;
        if (!pathLoader("fusion", &s.fusionPathField, "load", &path, s)) return false;
        s.scene.fusion.emplace();
        s.scene.fusion->dataset = path;
        return true;
    }
    Fusion& f = *s.scene.fusion;
    bool changed = false;
    ImGui::TextDisabled("%s", f.dataset.c_str());
    int mode = int(f.mode);
    if (ImGui::Combo("mode##fusion", &mode, "checkerboard\0split at a plane\0colour from the second\0sum\0"))
        f.mode = FusionMode(mode), changed = true;
    if (f.mode == FusionMode::Checkerboard) {
        float size = float(f.checkerSize);
        if (ImGui::SliderFloat("checker size", &size, 1.0f, 64.0f, "%.0f voxels")) f.checkerSize = size, changed = true;
    }
    if (f.mode == FusionMode::Split) {
        glm::vec3 n(f.splitNormal);
        if (ImGui::DragFloat3("split normal", &n.x, 0.01f, -1.0f, 1.0f) && glm::length(n) > 1e-3f)
            f.splitNormal = glm::dvec3(n), changed = true;
    }
    if (ImGui::SmallButton("remove the second volume")) s.scene.fusion.reset(), changed = true;
    return changed;
}

bool clipPlaneSection(State& s) {
    if (!ImGui::CollapsingHeader("clip planes", s.scene.clipPlanes.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    std::vector<ClipPlane>& planes = s.scene.clipPlanes;
    const glm::dvec3 centre = glm::dvec3(s.volume->dims()) * 0.5;
    const float reach = 0.5f * float(glm::length(glm::dvec3(s.volume->dims())));
    bool changed = false;
    for (std::size_t i = 0; i < planes.size(); ++i) {
        ImGui::PushID(int(i));
        ImGui::ColorButton("##colour", ImGui::ColorConvertU32ToFloat4(kPlaneColours[i]),
                           ImGuiColorEditFlags_NoTooltip, ImVec2(ImGui::GetFrameHeight(), ImGui::GetFrameHeight()));
        ImGui::SameLine();
        glm::vec3 n(glm::normalize(planes[i].normal));
        ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);
        if (ImGui::DragFloat3("##normal", &n.x, 0.01f, -1.0f, 1.0f, "%.2f") && glm::length(n) > 1e-3f)
            planes[i].normal = glm::dvec3(n), changed = true;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("the normal: the side it points into is kept");
        ImGui::SameLine();
        if (ImGui::SmallButton("remove")) {
            planes.erase(planes.begin() + std::ptrdiff_t(i));
            ImGui::PopID();
            return true;
        }
        // The plane's offset from the centre along its normal, in voxels.
        const glm::dvec3 unit = glm::normalize(planes[i].normal);
        float offset = float(glm::dot(planes[i].point - centre, unit));
        if (ImGui::SliderFloat("offset", &offset, -reach, reach, "%.1f voxels"))
            planes[i].point = centre + double(offset) * unit, changed = true;
        ImGui::PopID();
    }
    if (planes.size() < kMaxClipPlanes && ImGui::Button("add a plane (cuts away the near half)")) {
        // Through the centre, keeping the far side: the volume is opened towards the viewer.
        const Camera cam = Camera::make(s.scene.camera, s.volume->extent(), std::max(1, s.fbWidth), std::max(1, s.fbHeight));
        planes.push_back({centre, cam.forward});
        changed = true;
    }
    ImGui::TextDisabled("drag a plane's handle in the image to move it");
    return changed;
}

// The polygon where a plane cuts the box [0, extent]: the points where it
// crosses the box's 12 edges, in order around their centre.
std::vector<glm::dvec3> planeOutline(glm::dvec3 extent, glm::dvec3 point, glm::dvec3 normal) {
    std::vector<glm::dvec3> out;
    for (int axis = 0; axis < 3; ++axis)
        for (int corner = 0; corner < 4; ++corner) {
            glm::dvec3 a(0.0);
            a[(axis + 1) % 3] = corner & 1 ? extent[(axis + 1) % 3] : 0.0;
            a[(axis + 2) % 3] = corner & 2 ? extent[(axis + 2) % 3] : 0.0;
            glm::dvec3 b = a;
            b[axis] = extent[axis];
            const double da = glm::dot(a - point, normal), db = glm::dot(b - point, normal);
            if ((da < 0.0) != (db < 0.0)) out.push_back(a + (da / (da - db)) * (b - a));
        }
    if (out.size() < 3) return {};
    glm::dvec3 centre(0.0);
    for (const glm::dvec3& p : out) centre += p / double(out.size());
    const glm::dvec3 u = glm::normalize(out[0] - centre), v = glm::cross(normal, u);
    std::sort(out.begin(), out.end(), [&](const glm::dvec3& p, const glm::dvec3& q) {
        return std::atan2(glm::dot(p - centre, v), glm::dot(p - centre, u)) <
               std::atan2(glm::dot(q - centre, v), glm::dot(q - centre, u));
    });
    return out;
}

// A world point on the screen, in ImGui's display coordinates.
struct Projector {
    Camera cam;
    glm::dvec2 scale;  // display points per image pixel
    bool project(glm::dvec3 p, ImVec2* out) const {
        const glm::dvec3 q = p - cam.position;
        double depth = 1.0;
        if (cam.projection == Projection::Perspective) {
            depth = glm::dot(q, cam.forward);
            if (depth <= 1e-6) return false;
        }
        const double px = 0.5 * cam.width + glm::dot(q, cam.right) / (depth * cam.pixelScale);
        const double py = 0.5 * cam.height + glm::dot(q, cam.down) / (depth * cam.pixelScale);
        *out = ImVec2(float(px * scale.x), float(py * scale.y));
        return true;
    }
};

Projector projector(const State& s) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const int w = std::max(1, s.fbWidth), h = std::max(1, s.fbHeight);
    return {Camera::make(s.scene.camera, s.volume->extent(), w, h), {display.x / w, display.y / h}};
}

}  // namespace

bool sceneVolumeSections(State& s) {
    bool changed = labelSection(s);
    changed |= fusionSection(s);
    changed |= clipPlaneSection(s);
    return changed;
}

std::vector<ClipPlaneHandle> clipPlaneHandles(const State& s) {
    std::vector<ClipPlaneHandle> handles;
    const Projector proj = projector(s);
    const glm::dvec3 spacing = s.volume->spacing();
    for (const ClipPlane& plane : s.scene.clipPlanes) {
        ClipPlaneHandle h;
        const glm::dvec3 n = glm::normalize(plane.normal), point = plane.point * spacing;
        const std::vector<glm::dvec3> outline = planeOutline(s.volume->extent(), point, n);
        glm::dvec3 centre = point;
        if (!outline.empty()) {
            centre = glm::dvec3(0.0);
            for (const glm::dvec3& p : outline) centre += p / double(outline.size());
        }
        h.arrowLength = 0.15 * glm::length(s.volume->extent());
        ImVec2 c, tip;
        h.visible = proj.project(centre, &c) && proj.project(centre + h.arrowLength * n, &tip);
        h.centre = glm::vec2(c.x, c.y), h.tip = glm::vec2(tip.x, tip.y);
        for (const glm::dvec3& p : outline) {
            ImVec2 q;
            if (proj.project(p, &q)) h.outline.emplace_back(q.x, q.y);
        }
        handles.push_back(h);
    }
    return handles;
}

void drawClipPlanes(const State& s, ImDrawList* fg) {
    const std::vector<ClipPlaneHandle> handles = clipPlaneHandles(s);
    const float scale = s.contentScale;
    for (std::size_t i = 0; i < handles.size(); ++i) {
        const ClipPlaneHandle& h = handles[i];
        if (!h.visible) continue;
        const ImU32 colour = kPlaneColours[i % kMaxClipPlanes];
        std::vector<ImVec2> points;
        for (const glm::vec2& p : h.outline) points.emplace_back(p.x, p.y);
        if (points.size() >= 3) fg->AddPolyline(points.data(), int(points.size()), colour, ImDrawFlags_Closed, 2.0f * scale);
        const bool active = s.draggingPlane == int(i);
        fg->AddLine(ImVec2(h.centre.x, h.centre.y), ImVec2(h.tip.x, h.tip.y), colour, 2.0f * scale);
        fg->AddCircleFilled(ImVec2(h.tip.x, h.tip.y), 3.0f * scale, colour);
        fg->AddCircleFilled(ImVec2(h.centre.x, h.centre.y), (active ? 9.0f : 7.0f) * scale, colour);
        fg->AddCircle(ImVec2(h.centre.x, h.centre.y), (active ? 9.0f : 7.0f) * scale, IM_COL32(0, 0, 0, 200), 0,
                      1.5f * scale);
    }
}

int clipPlaneAt(const State& s, double x, double y) {
    const std::vector<ClipPlaneHandle> handles = clipPlaneHandles(s);
    for (std::size_t i = 0; i < handles.size(); ++i)
        if (handles[i].visible && glm::length(handles[i].centre - glm::vec2(x, y)) <= 10.0f * s.contentScale)
            return int(i);
    return -1;
}

void dragClipPlane(State& s, int index, double dx, double dy) {
    const std::vector<ClipPlaneHandle> handles = clipPlaneHandles(s);
    if (index < 0 || index >= int(handles.size()) || !handles[std::size_t(index)].visible) return;
    const ClipPlaneHandle& h = handles[std::size_t(index)];
    // The mouse's motion along the arrow's screen direction moves the plane
    // along its normal: the arrow's length on screen is arrowLength in the world.
    const glm::vec2 arrow = h.tip - h.centre;
    const float length2 = glm::dot(arrow, arrow);
    if (length2 < 4.0f) return;  // the normal points (nearly) at the viewer: no direction to drag
    const double along = double(glm::dot(glm::vec2(float(dx), float(dy)), arrow)) / double(length2) * h.arrowLength;
    ClipPlane& plane = s.scene.clipPlanes[std::size_t(index)];
    const glm::dvec3 spacing = s.volume->spacing();
    plane.point = (plane.point * spacing + along * glm::normalize(plane.normal)) / spacing;
}

}  // namespace voxlab::viewer
