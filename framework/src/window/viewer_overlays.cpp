// voxlab viewer: what is drawn over the image: the split view's divider
// and labels, the status line with the refinement's progress mark, the
// checkerboard's explanation, a deck's caption, the ray profile's pixel,
// shader errors (folded), messages and the keys.
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "viewer_state.h"
#include "voxlab/camera.h"
#include "voxlab/slice_viewer.h"

namespace voxlab::viewer {

namespace {

// The split view's divider and labels, and why a release has nothing to compare with.
void splitOverlay(State& s, ImDrawList* fg, ImVec2 size, float scale) {
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

}

// `text` in lines at most `width` wide, broken after a '/' (a path has no
// spaces to wrap at); a part wider than that alone stays whole.
std::vector<std::string> pathLines(const std::string& text, float width) {
    std::vector<std::string> lines(1);
    for (std::size_t from = 0; from < text.size();) {
        std::size_t to = text.find('/', from);
        to = to == std::string::npos ? text.size() : to + 1;
        const std::string part = text.substr(from, to - from);
        if (!lines.back().empty() && ImGui::CalcTextSize((lines.back() + part).c_str()).x > width) lines.emplace_back();
        lines.back() += part;
        from = to;
    }
    return lines;
}

// Frame time, bottom right, always; in the samples view the samples too;
// while the image refines, a small pie of its progress.
void statusLine(const State& s, ImDrawList* fg, ImVec2 size, float scale) {
    char samples[128] = "";
    if (s.samplesShown && s.samplesFull > 0)
        std::snprintf(samples, sizeof samples, "  samples %.3g of %.3g (%.0f%% skipped)", s.samplesTaken,
                      s.samplesFull, 100.0 * std::max(0.0, 1.0 - s.samplesTaken / s.samplesFull));
    else if (s.showSamples)
        std::snprintf(samples, sizeof samples, "  samples: ray casters without a cutting plane only");
    char quality[96] = "";
    if (s.coarseShown && s.coarseVolume) {
        const glm::ivec3 d = s.coarseVolume->dims();
        std::snprintf(quality, sizeof quality, "  moving: level %d of the pyramid (%dx%dx%d)%s", s.coarseLevel, d.x, d.y,
                      d.z, coarseFiltering(s.scene).c_str());
    } else if (s.tiling.active) {
        std::snprintf(quality, sizeof quality, "  rendering %dx%d: %d%%", s.tiling.width, s.tiling.height,
                      int(100.0 * s.tiling.done / std::max(1, s.tiling.height)));
    } else if (s.interactive && s.refineStep == 0) {
        std::snprintf(quality, sizeof quality, "  moving: reduced size, double step");
    } else if (s.interactive) {
        std::snprintf(quality, sizeof quality, "  refining %d/%d", s.refineStep, s.refineSteps);
    }
    char line[320];
    std::snprintf(line, sizeof line, "%s  render %.1f ms (%.1f frames/s)  %dx%d%s%s", s.scene.renderer.c_str(),
                  s.renderMs, s.renderMs > 0 ? 1000.0 / s.renderMs : 0.0, s.imageWidth, s.imageHeight, quality, samples);
    const ImVec2 t = ImGui::CalcTextSize(line);
    fg->AddRectFilled(ImVec2(size.x - t.x - 18 * scale, size.y - t.y - 14 * scale), ImVec2(size.x, size.y),
                      IM_COL32(0, 0, 0, 150));
    fg->AddText(ImVec2(size.x - t.x - 10 * scale, size.y - t.y - 8 * scale), IM_COL32(230, 230, 230, 255), line);
    // Where P saved the window, for a while, over the status line: the full
    // path, broken after a '/' where it is wider than the window.
    if (!s.lastScreenshot.empty() && Clock::now() < s.lastScreenshotUntil) {
        const std::vector<std::string> lines = pathLines("screenshot saved: " + s.lastScreenshot, size.x - 30 * scale);
        const float h = ImGui::GetTextLineHeight();
        float y = size.y - t.y - 20 * scale - h * float(lines.size());
        float widest = 0.0f;
        for (const std::string& l : lines) widest = std::max(widest, ImGui::CalcTextSize(l.c_str()).x);
        fg->AddRectFilled(ImVec2(size.x - widest - 18 * scale, y - 4 * scale), ImVec2(size.x, y + h * float(lines.size()) + 4 * scale),
                          IM_COL32(0, 0, 0, 170));
        for (const std::string& l : lines) {
            fg->AddText(ImVec2(size.x - ImGui::CalcTextSize(l.c_str()).x - 10 * scale, y), IM_COL32(160, 230, 160, 255), l.c_str());
            y += h;
        }
    }
    if (!s.interactive) return;
    // The progress mark: a pie that fills as the resolution doubles.
    const float r = 0.5f * t.y, cx = size.x - t.x - 18 * scale - r - 8 * scale, cy = size.y - 0.5f * t.y - 8 * scale;
    float done = s.refineSteps > 0 ? float(s.refineStep) / float(s.refineSteps + 1) : 0.0f;
    if (s.tiling.active)  // this step's share, plus the part of it already drawn
        done += float(s.tiling.done) / float(std::max(1, s.tiling.height)) / float(s.refineSteps + 1);
    fg->AddCircleFilled(ImVec2(cx, cy), r + 2, IM_COL32(0, 0, 0, 150));
    fg->AddCircle(ImVec2(cx, cy), r, IM_COL32(255, 200, 80, 255), 24, 1.5f * scale);
    if (done > 0.0f) {
        fg->PathLineTo(ImVec2(cx, cy));
        fg->PathArcTo(ImVec2(cx, cy), r, -1.5707963f, -1.5707963f + 6.2831853f * done, 24);
        fg->PathFillConvex(IM_COL32(255, 200, 80, 255));
    }
}

// The first line of a compiler's message that says "error", and the rest
// (Mesa lists every candidate overload: dozens of lines for one mistake).
std::pair<std::string, std::string> foldedMessage(const std::string& text) {
    std::vector<std::string> lines;
    for (std::size_t a = 0; a <= text.size();) {
        std::size_t b = text.find('\n', a);
        if (b == std::string::npos) b = text.size();
        if (b > a) lines.push_back(text.substr(a, b - a));
        a = b + 1;
    }
    if (lines.empty()) return {"", ""};
    std::size_t first = 0;
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (lines[i].find("error") != std::string::npos) {
            first = i;
            break;
        }
    std::string rest;
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (i != first) rest += lines[i] + "\n";
    return {lines[first], rest};
}

// A side's render error, or a shader that no longer compiles (the last good
// one keeps rendering): the first error line, the rest folded under it.
void errorBox(const State& s, ImVec2 size, float scale, float top) {
    std::vector<std::string> errors;
    for (const Side* side : {&s.main, &s.other}) {
        if (!side->engine) continue;
        if (!side->error.empty()) errors.push_back(side->error);
        if (!side->engine->shaderError().empty())
            errors.push_back(side->engine->shaderError() + "\n(showing the last shader that compiled)");
    }
    if (errors.empty()) return;
    ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, std::max(top, 10 * scale)), ImGuiCond_Always, ImVec2(0.5f, 0.0f));
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(size.x * 0.8f, size.y * 0.6f));
    ImGui::SetNextWindowBgAlpha(0.9f);
    ImGui::Begin("shader error", nullptr,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings);
    ImGui::PushTextWrapPos(size.x * 0.78f);
    for (std::size_t i = 0; i < errors.size(); ++i) {
        const auto [first, rest] = foldedMessage(errors[i]);
        ImGui::PushID(int(i));
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", first.c_str());
        const int more = int(std::count(rest.begin(), rest.end(), '\n'));
        if (more > 0 && ImGui::TreeNode("more", "%d more line%s", more, more == 1 ? "" : "s")) {
            ImGui::TextUnformatted(rest.c_str());
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    ImGui::PopTextWrapPos();
    ImGui::End();
}

// Text on a dark plate, centred on x.
void plateText(ImDrawList* fg, ImFont* font, float fontSize, ImVec2 centreTop, ImU32 colour, const std::string& text,
               float wrap) {
    const ImVec2 t = font->CalcTextSizeA(fontSize, FLT_MAX, wrap, text.c_str());
    const ImVec2 at(centreTop.x - 0.5f * t.x, centreTop.y);
    fg->AddRectFilled(ImVec2(at.x - 12, at.y - 8), ImVec2(at.x + t.x + 12, at.y + t.y + 8), IM_COL32(0, 0, 0, 190), 6);
    fg->AddText(font, fontSize, at, colour, text.c_str(), nullptr, wrap);
}

// A deck's caption, large, above the bottom edge; the slide number at the
// bottom left in the caption's font. Both go on the background list: under
// every panel, tooltip and window, so that none of them is ever covered.
void deckCaption(const State& s, ImDrawList* bg, ImVec2 size, float scale) {
    if (!s.deck) return;
    const Slide& slide = s.deck->slides[std::size_t(s.slide)];
    ImFont* font = captionFont();
    const float px = font->FontSize * (font == ImGui::GetIO().Fonts->Fonts[0] ? 1.7f * ImGui::GetIO().FontGlobalScale : 1.0f);
    const std::string text = slide.caption.empty() ? slide.scene.renderer : slide.caption;
    const float wrap = size.x * 0.8f;
    const float height = font->CalcTextSizeA(px, FLT_MAX, wrap, text.c_str()).y;
    plateText(bg, font, px, ImVec2(size.x * 0.5f, size.y - height - 56 * scale), IM_COL32(255, 255, 255, 255), text, wrap);
    char number[32];
    std::snprintf(number, sizeof number, "%d / %zu", s.slide + 1, s.deck->slides.size());
    const float numberPx = 0.6f * px;  // half again the text's size, as large as the scale makes the caption
    const ImVec2 t = font->CalcTextSizeA(numberPx, FLT_MAX, 0.0f, number);
    const ImVec2 at(14 * scale, size.y - t.y - 10 * scale);
    bg->AddRectFilled(ImVec2(at.x - 6 * scale, at.y - 4 * scale), ImVec2(at.x + t.x + 6 * scale, at.y + t.y + 4 * scale),
                      IM_COL32(0, 0, 0, 150), 4 * scale);
    bg->AddText(font, numberPx, at, IM_COL32(230, 230, 230, 255), number);
}

// Where the ray profile was taken: a ring on that pixel while the camera is
// the one it was taken with.
void profileMarker(const State& s, ImDrawList* fg, ImVec2 size, float scale) {
    if (!s.showProfile || !s.profile || s.fbWidth <= 0 || s.fbHeight <= 0) return;
    const CameraSpec& a = s.profileCamera;
    const CameraSpec& b = s.scene.camera;
    if (a.view != b.view || a.azimuth != b.azimuth || a.elevation != b.elevation || a.distance != b.distance ||
        a.fov != b.fov || a.zoom != b.zoom || a.pan != b.pan || a.projection != b.projection)
        return;
    const ImVec2 p((s.profilePixel.x + 0.5f) * size.x / float(s.fbWidth),
                   (s.profilePixel.y + 0.5f) * size.y / float(s.fbHeight));
    const float r = 7.0f * scale;
    fg->AddCircle(p, r + 1.5f * scale, IM_COL32(0, 0, 0, 200), 24, 3.0f * scale);
    fg->AddCircle(p, r, IM_COL32(255, 230, 60, 255), 24, 1.8f * scale);
    for (const ImVec2 d : {ImVec2(1, 0), ImVec2(-1, 0), ImVec2(0, 1), ImVec2(0, -1)})
        fg->AddLine(ImVec2(p.x + d.x * r * 1.5f, p.y + d.y * r * 1.5f), ImVec2(p.x + d.x * r * 2.6f, p.y + d.y * r * 2.6f),
                    IM_COL32(255, 230, 60, 255), 1.8f * scale);
}

void helpWindow(State& s, ImVec2 size) {
    {
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
                                 {"+  -", "UI scale (presentation mode; also --ui-scale)"},
                                 {"arrows, Page Up/Down", "a deck's next / previous slide (--deck)"},
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

}  // namespace

void drawOverlays(State& s) {
    ImDrawList* fg = ImGui::GetForegroundDrawList();
    ImDrawList* bg = ImGui::GetBackgroundDrawList();
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    const float scale = s.contentScale;

    // The slice planes in the 3D view.
    if (s.showSlices && s.volume) {
        const Camera camera = Camera::make(s.scene.camera, s.volume->extent(), s.fbWidth, s.fbHeight);
        drawSlicePlanes(bg, camera, s.volume->extent(), s.volume->spacing(), s.slices.voxel, ImVec2(0, 0), size);
    }
    if (s.volume) drawClipPlanes(s, bg);  // under the panels, over the image
    splitOverlay(s, fg, size, scale);
    profileMarker(s, fg, size, scale);
    deckCaption(s, bg, size, scale);
    statusLine(s, bg, size, scale);  // under the panels too: never over a control
    float noticeBottom = 0.0f;  // the error box goes below the checkerboard's line
    if (!s.stubNotice.empty()) {  // the checkerboard, explained: centred in the space right of the controls
        const float left = s.showPanel ? s.panelRight + 10 * scale : 0.0f;
        const float wrap = std::max(200.0f, 0.9f * (size.x - left) - 24 * scale);
        plateText(fg, ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(0.5f * (left + size.x), 12 * scale),
                  IM_COL32(255, 200, 90, 255), s.stubNotice, wrap);
        noticeBottom = 12 * scale + ImGui::GetFont()->CalcTextSizeA(ImGui::GetFontSize(), FLT_MAX, wrap, s.stubNotice.c_str()).y +
                       8 + 6 * scale;
    }
    errorBox(s, size, scale, noticeBottom);
    if (!s.toast.empty() && Clock::now() < s.toastUntil) {
        const ImVec2 tt = ImGui::CalcTextSize(s.toast.c_str());
        // (Above the screenshot's path, when it is shown.)
        const bool path = !s.lastScreenshot.empty() && Clock::now() < s.lastScreenshotUntil;
        const ImVec2 at(size.x * 0.5f - tt.x * 0.5f, size.y - 70 * scale - (path ? 4.0f * ImGui::GetTextLineHeight() : 0.0f));
        fg->AddRectFilled(ImVec2(at.x - 10, at.y - 6), ImVec2(at.x + tt.x + 10, at.y + tt.y + 6), IM_COL32(20, 20, 30, 220), 6);
        fg->AddText(at, IM_COL32(255, 255, 255, 255), s.toast.c_str());
    }
    if (s.showHelp) helpWindow(s, size);
}

}  // namespace voxlab::viewer
