// voxlab viewer: the size of everything ImGui draws (presentation mode).
//
// A lecture hall reads a projector from 20 m: the viewer's text must be large
// and sharp. ImGui's built-in font is a 13 px bitmap; scaled up with
// FontGlobalScale it turns blurry. So the font atlas is rebuilt from a
// TrueType font at the new size whenever the scale changes (--ui-scale, or
// the + and - keys), and the style's sizes are scaled from an unscaled copy
// (ImGuiStyle::ScaleAllSizes multiplies, so scaling twice would compound).
// The font is DejaVu Sans (Debian's fonts-dejavu-core); without it the
// built-in font is scaled, which still works, only softer.
#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "viewer_state.h"

namespace voxlab::viewer {

namespace {

constexpr float kFontPixels = 15.0f;     // at scale 1: a little larger than ImGui's 13 px, easier to read
constexpr float kCaptionPixels = 26.0f;  // a deck's captions

const char* fontFile() {
    static const char* const candidates[] = {
        "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",  // Debian, Ubuntu (fonts-dejavu-core)
        "/usr/share/fonts/TTF/DejaVuSans.ttf",              // Arch, Fedora
        "/Library/Fonts/Arial Unicode.ttf",                 // macOS
    };
    for (const char* f : candidates)
        if (std::filesystem::exists(f)) return f;
    return nullptr;
}

ImGuiStyle& baseStyle() {
    static ImGuiStyle base = [] {
        ImGuiStyle style;
        ImGui::StyleColorsDark(&style);
        style.WindowRounding = 6.0f;
        style.FrameRounding = 3.0f;
        return style;
    }();
    return base;
}

}  // namespace

float clampUiScale(float scale) {
    if (!std::isfinite(scale)) return 1.0f;
    return std::clamp(std::round(scale * 4.0f) / 4.0f, 0.75f, 4.0f);  // quarter steps
}

void applyUiScale(State& s, float userScale, float windowScale) {
    s.uiScale = clampUiScale(userScale);
    const float scale = std::max(1.0f, windowScale) * s.uiScale;
    ImGuiIO& io = ImGui::GetIO();
    io.Fonts->Clear();
    static bool warned = false;
    if (const char* file = fontFile()) {
        io.Fonts->AddFontFromFileTTF(file, std::round(kFontPixels * scale));
        io.Fonts->AddFontFromFileTTF(file, std::round(kCaptionPixels * scale));  // captionFont()
        io.FontGlobalScale = 1.0f;
    } else {
        if (!warned) std::fprintf(stderr, "voxlab: no DejaVu Sans font (apt-get install fonts-dejavu-core): "
                                          "using ImGui's built-in font, scaled\n");
        warned = true;
        io.Fonts->AddFontDefault();
        io.FontGlobalScale = scale;
    }
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    ImGui_ImplOpenGL3_CreateFontsTexture();
    ImGui::GetStyle() = baseStyle();
    ImGui::GetStyle().ScaleAllSizes(scale);
    if (s.deck) {  // a lecture's caption lies under the panels: none of it shows through them
        ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
        ImGui::GetStyle().Colors[ImGuiCol_PopupBg].w = 1.0f;
    }
    if (s.contentScale != scale) s.dirty = true;  // the wireframes' lines are as wide as the scale
    s.contentScale = scale;
    s.relayout = true;  // panels move to the places of this scale
}

ImFont* captionFont() {
    ImFontAtlas* fonts = ImGui::GetIO().Fonts;
    return fonts->Fonts.Size > 1 ? fonts->Fonts[1] : fonts->Fonts[0];
}

}  // namespace voxlab::viewer
