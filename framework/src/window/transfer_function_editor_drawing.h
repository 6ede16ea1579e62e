// voxlab: drawing and input helpers shared by the transfer-function editors
// (transfer_function_editor.cpp, transfer_function_2d_editor.cpp). Private
// to src/window/.
#pragma once

#include <cmath>

#include <imgui.h>
#include <imgui_internal.h>  // SetItemUsingMouseWheel (ImGui 1.86)

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/transfer_function_editor.h"

namespace voxlab::tf_editor {

// State an editor keeps between frames (a drag, a zoom), found through the
// current window's ImGui storage under `id`: a new ImGui context starts with
// fresh states. (The states themselves live here; those of a destroyed
// context are a few bytes each, left until exit.)
template <typename State>
State& persistentState(ImGuiID id) {
    static std::vector<std::unique_ptr<State>> states;
    int* slot = ImGui::GetStateStorage()->GetIntRef(id, 0);
    if (*slot <= 0 || *slot > int(states.size())) {
        states.push_back(std::make_unique<State>());
        *slot = int(states.size());
    }
    return *states[std::size_t(*slot - 1)];
}

// Which editor was clicked last: each click takes a new stamp, and Delete
// acts only on the editor holding the newest one.
inline std::uint64_t& clickClock() {
    static std::uint64_t clock = 0;
    return clock;
}

// Handles: a disc of the element's own colour inside a dark outline with a
// light ring; the selected one larger, with a ring in the highlight colour.
constexpr float kHandleRadius = 5.0f;
// A press this close (pixels) to a handle's centre grabs it.
constexpr float kHitRadius = 9.0f;

// The plot frame both editors share: `height` pixels of plot plus padding,
// across the available width at the cursor, taken by an invisible button
// (left and right clicks); over it the mouse wheel scales `*zoom` within
// [1, maxZoom].
struct EditorFrame {
    ImVec2 origin, max;  // the frame, padding included
    float width = 0.0f, pad = 0.0f;
    bool hovered = false, active = false;
    ImVec2 plotMin() const { return ImVec2(origin.x + pad, origin.y + pad); }
    ImVec2 plotMax() const { return ImVec2(max.x - pad, max.y - pad); }
};

inline EditorFrame editorFrame(float height, float* zoom, float maxZoom) {
    EditorFrame f;
    f.pad = kTransferFunctionEditorPadding;
    f.origin = ImGui::GetCursorScreenPos();
    f.width = std::max(ImGui::GetContentRegionAvail().x, 4.0f * f.pad + 40.0f);
    const ImVec2 size(f.width, std::max(height, 20.0f) + 2.0f * f.pad);
    f.max = ImVec2(f.origin.x + size.x, f.origin.y + size.y);
    ImGui::InvisibleButton("##graph", size, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    f.hovered = ImGui::IsItemHovered();
    f.active = ImGui::IsItemActive();
    if (f.hovered) {
        ImGui::SetItemUsingMouseWheel();
        const float wheel = ImGui::GetIO().MouseWheel;
        if (wheel != 0.0f) *zoom = std::clamp(*zoom * std::pow(1.25f, wheel), 1.0f, maxZoom);
    }
    return f;
}

inline ImU32 colour(const glm::vec3& rgb, float alpha) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(rgb.r, rgb.g, rgb.b, alpha));
}

inline ImU32 styleColour(ImGuiCol which, float alphaScale = 1.0f) {
    ImVec4 c = ImGui::GetStyleColorVec4(which);
    c.w *= alphaScale;
    return ImGui::ColorConvertFloat4ToU32(c);
}

inline ImU32 highlightColour() { return IM_COL32(255, 200, 60, 255); }

inline float distanceSquared(ImVec2 a, ImVec2 b) {
    const float dx = a.x - b.x, dy = a.y - b.y;
    return dx * dx + dy * dy;
}

inline void drawHandle(ImDrawList* draw, ImVec2 centre, ImU32 fill, bool selected, bool hovered) {
    const float r = kHandleRadius + (selected ? 1.5f : 0.0f) + (hovered ? 1.0f : 0.0f);
    if (selected) draw->AddCircle(centre, r + 3.0f, highlightColour(), 0, 2.0f);
    draw->AddCircleFilled(centre, r + 1.5f, IM_COL32(15, 15, 20, 230));
    draw->AddCircleFilled(centre, r, fill | IM_COL32_A_MASK);
    draw->AddCircle(centre, r, selected ? highlightColour() : IM_COL32(235, 235, 235, 220), 0, 1.0f);
}

// A quadrilateral (p0..p3 in order) or triangle with one colour per corner,
// interpolated across it (Gouraud), e.g. the colour-filled area under a
// piecewise-linear curve. Not anti-aliased: used for fills only.
inline void fillQuad(ImDrawList* draw, ImVec2 p0, ImVec2 p1, ImVec2 p2, ImVec2 p3, ImU32 c0, ImU32 c1, ImU32 c2,
                     ImU32 c3) {
    const ImVec2 uv = ImGui::GetFontTexUvWhitePixel();
    const ImDrawIdx base = ImDrawIdx(draw->_VtxCurrentIdx);
    draw->PrimReserve(6, 4);
    draw->PrimWriteIdx(base), draw->PrimWriteIdx(ImDrawIdx(base + 1)), draw->PrimWriteIdx(ImDrawIdx(base + 2));
    draw->PrimWriteIdx(base), draw->PrimWriteIdx(ImDrawIdx(base + 2)), draw->PrimWriteIdx(ImDrawIdx(base + 3));
    draw->PrimWriteVtx(p0, uv, c0), draw->PrimWriteVtx(p1, uv, c1);
    draw->PrimWriteVtx(p2, uv, c2), draw->PrimWriteVtx(p3, uv, c3);
}

inline void fillTriangle(ImDrawList* draw, ImVec2 p0, ImVec2 p1, ImVec2 p2, ImU32 c0, ImU32 c1, ImU32 c2) {
    const ImVec2 uv = ImGui::GetFontTexUvWhitePixel();
    draw->PrimReserve(3, 3);
    draw->PrimVtx(p0, uv, c0), draw->PrimVtx(p1, uv, c1), draw->PrimVtx(p2, uv, c2);
}

// Text with a dark backing, readable over histograms and fills.
inline void drawLabel(ImDrawList* draw, ImVec2 pos, const char* text, ImU32 colour) {
    const ImVec2 size = ImGui::CalcTextSize(text);
    draw->AddRectFilled(ImVec2(pos.x - 2, pos.y), ImVec2(pos.x + size.x + 2, pos.y + size.y), IM_COL32(0, 0, 0, 110),
                        2.0f);
    draw->AddText(pos, colour, text);
}

// A data value for labels and tooltips: up to 5 significant digits, no
// trailing zeros ("38", "0.25", "1.234e+05").
inline std::string formatValue(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.5g", v);
    return text;
}

// The visible part of an ImGui label (the text before "##").
inline std::string visibleLabel(const char* label) {
    const std::string s = label ? label : "";
    return s.substr(0, s.find("##"));
}

inline bool keyPressed(ImGuiKey key) {
    const int index = ImGui::GetKeyIndex(key);
    return index >= 0 && ImGui::IsKeyPressed(index, false);
}

// Delete or Backspace, while this window has focus and no text is typed.
inline bool deletePressed() {
    if (ImGui::GetIO().WantTextInput || !ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows)) return false;
    return keyPressed(ImGuiKey_Delete) || keyPressed(ImGuiKey_Backspace);
}

// ImGui::InputText on a std::string (the buffer grows as the user types).
inline bool inputText(const char* label, std::string* text, ImGuiInputTextFlags flags = 0) {
    struct Resize {
        static int callback(ImGuiInputTextCallbackData* data) {
            if (data->EventFlag == ImGuiInputTextFlags_CallbackResize) {
                auto* s = static_cast<std::string*>(data->UserData);
                s->resize(std::size_t(data->BufTextLen));
                data->Buf = s->data();
            }
            return 0;
        }
    };
    return ImGui::InputText(label, text->data(), text->capacity() + 1, flags | ImGuiInputTextFlags_CallbackResize,
                            &Resize::callback, text);
}

}  // namespace voxlab::tf_editor
