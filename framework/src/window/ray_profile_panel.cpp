// voxlab: the ray-profile panel (see ray_profile_panel.h). Everything is
// drawn with the window's draw list: plots share one depth axis t, laid out
// top to bottom as value, opacity (compositing only), colour strips, axis.
#include "voxlab/ray_profile_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <imgui.h>

namespace voxlab {
namespace {

// Palette, chosen to read on ImGui's dark theme.
const ImU32 kValueColour = IM_COL32(96, 172, 255, 255);
const ImU32 kMaxColour = IM_COL32(255, 160, 64, 255);
const ImU32 kMinColour = IM_COL32(178, 128, 255, 255);
const ImU32 kMeanColour = IM_COL32(120, 220, 150, 255);
const ImU32 kThresholdColour = IM_COL32(240, 216, 80, 255);
const ImU32 kSampleOpacityColour = IM_COL32(230, 100, 90, 200);
const ImU32 kAccumulatedColour = IM_COL32(240, 240, 240, 255);
const ImU32 kStopColour = IM_COL32(255, 72, 72, 255);
const ImU32 kGridColour = IM_COL32(255, 255, 255, 28);
const ImU32 kFrameColour = IM_COL32(255, 255, 255, 70);
const ImU32 kPlotBackground = IM_COL32(16, 18, 22, 255);
const ImU32 kLabelColour = IM_COL32(200, 200, 205, 255);
const ImU32 kDimLabelColour = IM_COL32(140, 140, 150, 255);
const ImU32 kCursorColour = IM_COL32(255, 255, 255, 110);

ImU32 colourOf(const glm::vec4& c, float alpha = 1.0f) {
    const auto byte = [](float x) { return int(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f)); };
    return IM_COL32(byte(c.r), byte(c.g), byte(c.b), byte(alpha));
}

// Tick spacing 1, 2 or 5 times a power of ten giving about `count` ticks.
double niceTickStep(double span, int count) {
    if (!(span > 0.0)) return 1.0;
    const double raw = span / std::max(count, 1);
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * power >= raw) return m * power;
    return 10.0 * power;
}

void checkerboard(ImDrawList* dl, ImVec2 a, ImVec2 b, float cell) {
    dl->AddRectFilled(a, b, IM_COL32(90, 90, 96, 255));
    dl->PushClipRect(a, b, true);
    int row = 0;
    for (float y = a.y; y < b.y; y += cell, ++row)
        for (float x = a.x + ((row & 1) ? cell : 0.0f); x < b.x; x += 2.0f * cell)
            dl->AddRectFilled(ImVec2(x, y), ImVec2(x + cell, y + cell), IM_COL32(150, 150, 156, 255));
    dl->PopClipRect();
}

void dashedHorizontal(ImDrawList* dl, float x0, float x1, float y, ImU32 col, float dash) {
    for (float x = x0; x < x1; x += 2.0f * dash)
        dl->AddLine(ImVec2(x, y), ImVec2(std::min(x + dash, x1), y), col, 1.5f);
}

// A legend entry: a short line in the curve's colour and its name; returns
// the x after it.
float legendEntry(ImDrawList* dl, float x, float y, ImU32 col, const char* name, bool dashed = false) {
    const float len = ImGui::GetFontSize() * 1.2f;
    const float mid = y + ImGui::GetFontSize() * 0.5f;
    if (dashed) dashedHorizontal(dl, x, x + len, mid, col, len / 5.0f);
    else dl->AddLine(ImVec2(x, mid), ImVec2(x + len, mid), col, 2.5f);
    x += len + 4.0f;
    dl->AddText(ImVec2(x, y), kLabelColour, name);
    return x + ImGui::CalcTextSize(name).x + ImGui::GetFontSize();
}

struct Box {
    ImVec2 min, max;
    float width() const { return max.x - min.x; }
    float height() const { return max.y - min.y; }
};

// One plot frame: background, horizontal grid at the y ticks, the y labels
// to its left and its title inside the top-left corner.
void plotFrame(ImDrawList* dl, const Box& box, const char* title, const char* const* yLabels, const float* yFractions,
               int yCount) {
    dl->AddRectFilled(box.min, box.max, kPlotBackground, 3.0f);
    for (int i = 0; i < yCount; ++i) {
        const float y = box.max.y - yFractions[i] * box.height();
        dl->AddLine(ImVec2(box.min.x, y), ImVec2(box.max.x, y), kGridColour);
        const ImVec2 size = ImGui::CalcTextSize(yLabels[i]);
        const float ty = std::clamp(y - size.y * 0.5f, box.min.y - 2.0f, box.max.y - size.y + 2.0f);
        dl->AddText(ImVec2(box.min.x - size.x - 6.0f, ty), kDimLabelColour, yLabels[i]);
    }
    dl->AddRect(box.min, box.max, kFrameColour, 3.0f);
    dl->AddText(ImVec2(box.min.x + 6.0f, box.min.y + 3.0f), kDimLabelColour, title);
}

std::string shortNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

// The footer: the pixel's colour as a swatch with its numbers, why the ray
// stopped, and what the profile leaves out.
void footerLines(const RayProfile& profile) {
    if (profile.modelled && profile.hitsVolume) {
        const float side = ImGui::GetTextLineHeight();
        const ImVec2 at = ImGui::GetCursorScreenPos();
        ImDrawList* dl = ImGui::GetWindowDrawList();
        checkerboard(dl, at, ImVec2(at.x + side, at.y + side), side * 0.5f);
        const glm::vec4 r = profile.result;
        const glm::vec4 straight = r.a > 0.0f ? glm::vec4(glm::vec3(r) / r.a, r.a) : glm::vec4(0.0f);
        dl->AddRectFilled(at, ImVec2(at.x + side, at.y + side), colourOf(straight, r.a));
        dl->AddRect(at, ImVec2(at.x + side, at.y + side), kFrameColour);
        ImGui::Dummy(ImVec2(side, side));
        ImGui::SameLine();
        ImGui::TextDisabled("pixel  C %.3f %.3f %.3f  A %.3f  (before the background)", r.r, r.g, r.b, r.a);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("the ray's premultiplied colour C and opacity A;\n"
                              "the renderer shows C + (1 - A) background");
    }
    const bool stopped = profile.stoppedAt >= 0;
    const ImVec4 colour = stopped ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f)
                          : profile.hitsVolume && profile.modelled ? ImVec4(0.75f, 0.85f, 1.0f, 1.0f)
                                                                   : ImVec4(1.0f, 0.75f, 0.4f, 1.0f);
    ImGui::TextColored(colour, "%s", profile.why.c_str());
    if (!profile.note.empty()) ImGui::TextDisabled("note: %s", profile.note.c_str());
}

// The part of the ray on show, as fractions [lo, hi] of the whole ray: the
// mouse wheel zooms about the cursor, dragging pans, a double click shows
// the whole ray again. Kept in ImGui's state storage under the canvas's ID,
// and reset when the panel shows another pixel's ray.
struct DepthView {
    float lo = 0.0f, hi = 1.0f;
};

DepthView updateDepthView(const RayProfile& profile, bool hovered, bool active, float left, float right,
                          double minimumFraction) {
    ImGuiStorage* storage = ImGui::GetStateStorage();
    const ImGuiID loId = ImGui::GetID("view lo"), hiId = ImGui::GetID("view hi"), keyId = ImGui::GetID("view key");
    // A hash: unsigned, so that it wraps instead of overflowing (UBSan).
    const int key = int(unsigned(ImGui::GetID(profile.renderer.c_str())) ^ (unsigned(profile.px) * 73856093u) ^
                        (unsigned(profile.py) * 19349663u) ^ unsigned(profile.samples.size()));
    DepthView v;
    if (storage->GetInt(keyId, 0) == key) v.lo = storage->GetFloat(loId, 0.0f), v.hi = storage->GetFloat(hiId, 1.0f);
    const ImGuiIO& io = ImGui::GetIO();
    const float width = std::max(right - left, 1.0f);
    if (hovered && io.MouseWheel != 0.0f) {
        const float at = v.lo + std::clamp((io.MousePos.x - left) / width, 0.0f, 1.0f) * (v.hi - v.lo);
        const float scale = std::pow(0.8f, io.MouseWheel);
        const float span = std::clamp((v.hi - v.lo) * scale, float(minimumFraction), 1.0f);
        v.lo = at - (at - v.lo) / (v.hi - v.lo) * span;
        v.hi = v.lo + span;
    }
    if (active && io.MouseDelta.x != 0.0f) {
        const float shift = -io.MouseDelta.x / width * (v.hi - v.lo);
        v.lo += shift, v.hi += shift;
    }
    if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) v.lo = 0.0f, v.hi = 1.0f;
    // Keep the window inside the ray.
    const float span = std::min(v.hi - v.lo, 1.0f);
    v.lo = std::clamp(v.lo, 0.0f, 1.0f - span);
    v.hi = v.lo + span;
    storage->SetFloat(loId, v.lo);
    storage->SetFloat(hiId, v.hi);
    storage->SetInt(keyId, key);
    return v;
}

// The plots' layout and scales for one profile on one canvas, and its
// parts, each drawn by one method (top to bottom: legend, value plot,
// opacity plot for compositing, two colour strips, the depth axis; a left
// margin for the y labels).
struct ProfileCanvas {
    const RayProfile& profile;
    ImDrawList* dl = nullptr;
    ImVec2 origin;
    float em = 0.0f;
    int count = 0;
    bool hovered = false, active = false;
    bool composites = false, strips = false;
    float left = 0.0f, right = 0.0f, stripHeight = 0.0f, bottom = 0.0f, axisY = 0.0f;
    Box valueBox, opacityBox, sampleStrip, resultStrip;
    DepthView view;
    double tLo = 0.0, tHi = 1.0, vLo = 0.0, vHi = 1.0;
    int first = 0, last = 0;  // the samples in view (one more on each side, for the lines)
    float sampleWidth = 0.0f;

    ProfileCanvas(const RayProfile& p, ImVec2 canvasSize, const glm::dvec2& valueRange);
    float xOf(double t) const { return float(left + (t - tLo) / (tHi - tLo) * (right - left)); }
    float valueY(double v) const {
        const double f = std::clamp((v - vLo) / (vHi - vLo), -0.02, 1.02);
        return float(valueBox.max.y - f * valueBox.height());
    }
    float opacityY(double a) const { return float(opacityBox.max.y - std::clamp(a, 0.0, 1.0) * opacityBox.height()); }

    void legend() const;
    void frames() const;
    void depthAxis() const;
    template <class YOf>
    void polyline(const Box& box, ImU32 col, float thickness, YOf yOf) const;
    void valueLines() const;
    void opacityPlot() const;
    void colourStrips() const;
    void stopAndChoice() const;
    void stripLabels() const;
    void hoverSample() const;
};

ProfileCanvas::ProfileCanvas(const RayProfile& p, ImVec2 canvasSize, const glm::dvec2& valueRange) : profile(p) {
    em = ImGui::GetFontSize();
    count = int(profile.samples.size());
    origin = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("canvas", canvasSize);
    hovered = ImGui::IsItemHovered(), active = ImGui::IsItemActive();
    dl = ImGui::GetWindowDrawList();

    composites = profile.model == ProfileModel::Composite && profile.hitsVolume;
    strips = profile.model != ProfileModel::Isosurface && profile.modelled;
    left = origin.x + em * 3.6f, right = origin.x + canvasSize.x - em * 0.6f;
    stripHeight = em * 0.95f;
    const float gap = em * 0.6f, axisHeight = em * 2.4f, legendHeight = em * 1.5f;
    const float stripsHeight = strips ? 2.0f * stripHeight + 1.6f * gap : 0.0f;
    const float plotsHeight = canvasSize.y - legendHeight - stripsHeight - axisHeight;
    float y = origin.y + legendHeight;
    valueBox = Box{ImVec2(left, y), ImVec2(right, y + plotsHeight * (composites ? 0.55f : 1.0f))};
    y = valueBox.max.y;
    opacityBox = Box{ImVec2(left, y), ImVec2(right, y)};
    if (composites) {
        opacityBox = Box{ImVec2(left, y + gap), ImVec2(right, y + plotsHeight * 0.45f)};
        y = opacityBox.max.y;
    }
    sampleStrip = Box{ImVec2(left, y + gap), ImVec2(right, y + gap + stripHeight)};
    resultStrip = Box{ImVec2(left, sampleStrip.max.y + 0.6f * gap), ImVec2(right, sampleStrip.max.y + 0.6f * gap + stripHeight)};
    bottom = strips ? resultStrip.max.y : y;  // the lowest thing a vertical marker crosses
    axisY = bottom + 0.6f * gap;

    // The depth axis: the clipped ray, widened to hold every sample's
    // interval, of which the view shows a part.
    const double rayLo = std::min(profile.tEntry, profile.samples.front().t - 0.5 * profile.step);
    const double rayHi = std::max(profile.tExit, profile.samples.back().t + 0.5 * profile.step);
    view = updateDepthView(profile, hovered, active, left, right, std::min(1.0, 6.0 * profile.step / (rayHi - rayLo)));
    tLo = rayLo + view.lo * (rayHi - rayLo), tHi = rayLo + view.hi * (rayHi - rayLo);
    vLo = valueRange.x, vHi = valueRange.y > valueRange.x ? valueRange.y : valueRange.x + 1.0;
    first = std::clamp(int(std::floor((tLo - profile.tEntry) / profile.step - 0.5)) - 1, 0, count - 1);
    last = std::clamp(int(std::ceil((tHi - profile.tEntry) / profile.step - 0.5)) + 1, 0, count - 1);
    sampleWidth = (right - left) * float(profile.step / (tHi - tLo));
}

// The legend row above the plots; shorter names when the long ones do not fit.
void ProfileCanvas::legend() const {
    struct Entry {
        ImU32 colour;
        const char *name, *shortName;
        bool dashed;
    };
    std::vector<Entry> entries = {{kValueColour, "value", "value", false}};
    if (profile.model == ProfileModel::Minimum) entries.push_back({kMinColour, "running min", "min", false});
    else if (profile.model == ProfileModel::Mean) entries.push_back({kMeanColour, "running mean", "mean", false});
    else entries.push_back({kMaxColour, "running max", "max", false});
    if (profile.hasThreshold)
        entries.push_back({kThresholdColour, profile.model == ProfileModel::Isosurface ? "isovalue" : "threshold",
                           profile.model == ProfileModel::Isosurface ? "iso" : "thresh.", true});
    if (composites) {
        entries.push_back({kSampleOpacityColour, "sample opacity", "opacity", false});
        entries.push_back({kAccumulatedColour, "accumulated", "accum.", false});
    }
    if (profile.stoppedAt >= 0) entries.push_back({kStopColour, "stop", "stop", false});
    float needed = 0.0f;
    for (const Entry& e : entries) needed += em * 2.2f + 4.0f + ImGui::CalcTextSize(e.name).x;  // as legendEntry
    const bool compact = needed > right - origin.x - em;
    float x = origin.x + em * 0.5f;
    for (const Entry& e : entries)
        x = legendEntry(dl, x, origin.y + em * 0.1f, e.colour, compact ? e.shortName : e.name, e.dashed);
}

// Plot frames, with value ticks at round numbers of the data.
void ProfileCanvas::frames() const {
    const double step = niceTickStep(vHi - vLo, std::max(2, int(valueBox.height() / (em * 2.2f))));
    std::vector<std::string> texts;
    std::vector<float> fractions;
    for (double v = std::ceil(vLo / step) * step; v <= vHi + 1e-9 * step; v += step) {
        texts.push_back(shortNumber(std::abs(v) < 1e-9 * step ? 0.0 : v));
        fractions.push_back(float((v - vLo) / (vHi - vLo)));
    }
    std::vector<const char*> labels;
    for (const std::string& t : texts) labels.push_back(t.c_str());
    plotFrame(dl, valueBox, "value", labels.data(), fractions.data(), int(labels.size()));
    if (composites) {
        const char* opacityLabels[] = {"0", "0.5", "1"};
        const float opacityFractions[] = {0.0f, 0.5f, 1.0f};
        plotFrame(dl, opacityBox, "opacity", opacityLabels, opacityFractions, 3);
    }
}

// Depth ticks (grid lines through the plots, labels under the axis), the
// axis's name at the right and, while the mouse is over the plots, how to
// zoom at the left (the name shrinks to "t" if both do not fit).
void ProfileCanvas::depthAxis() const {
    const double tick = niceTickStep(tHi - tLo, std::max(2, int((right - left) / (em * 5.0f))));
    for (double t = std::ceil(tLo / tick) * tick; t <= tHi + 1e-9 * tick; t += tick) {
        const float x = xOf(t);
        dl->AddLine(ImVec2(x, valueBox.min.y), ImVec2(x, valueBox.max.y), kGridColour);
        if (composites) dl->AddLine(ImVec2(x, opacityBox.min.y), ImVec2(x, opacityBox.max.y), kGridColour);
        dl->AddLine(ImVec2(x, axisY), ImVec2(x, axisY + em * 0.35f), kFrameColour);
        const std::string text = shortNumber(std::abs(t) < 1e-9 * tick ? 0.0 : t);
        const ImVec2 size = ImGui::CalcTextSize(text.c_str());
        dl->AddText(ImVec2(std::clamp(x - size.x * 0.5f, left - em, right - size.x), axisY + em * 0.4f),
                    kDimLabelColour, text.c_str());
    }
    dl->AddLine(ImVec2(left, axisY), ImVec2(right, axisY), kFrameColour);
    const bool zoomed = view.hi - view.lo < 1.0f;
    const char* hint = zoomed ? "wheel: zoom  drag: pan  double-click: whole ray" : "wheel: zoom";
    const float hintWidth = hovered || zoomed ? ImGui::CalcTextSize(hint).x + em : 0.0f;
    const char* axisLabel = "t along the ray (world units)";
    if (left + hintWidth + ImGui::CalcTextSize(axisLabel).x > right) axisLabel = "t";
    const float textY = axisY + em * 1.35f;
    dl->AddText(ImVec2(right - ImGui::CalcTextSize(axisLabel).x, textY), kDimLabelColour, axisLabel);
    if (hintWidth > 0.0f) dl->AddText(ImVec2(left, textY), IM_COL32(120, 120, 130, 255), hint);
}

// A line through the samples in view, clipped to `box`.
template <class YOf>
void ProfileCanvas::polyline(const Box& box, ImU32 col, float thickness, YOf yOf) const {
    std::vector<ImVec2> line;
    for (int m = first; m <= last; ++m) line.push_back(ImVec2(xOf(profile.samples[m].t), yOf(profile.samples[m])));
    dl->PushClipRect(ImVec2(box.min.x, box.min.y - 1.0f), ImVec2(box.max.x, box.max.y + 1.0f), true);
    if (line.size() == 1) dl->AddCircleFilled(line[0], thickness + 1.0f, col);
    else dl->AddPolyline(line.data(), int(line.size()), col, ImDrawFlags_None, thickness);
    dl->PopClipRect();
}

// The threshold, the running statistic and the values (each sample marked
// when few are on show).
void ProfileCanvas::valueLines() const {
    if (profile.hasThreshold)
        dashedHorizontal(dl, valueBox.min.x, valueBox.max.x, valueY(profile.threshold), kThresholdColour, em * 0.4f);
    if (profile.model == ProfileModel::Minimum)
        polyline(valueBox, kMinColour, 2.0f, [&](const RaySample& s) { return valueY(s.runningMin); });
    else if (profile.model == ProfileModel::Mean)
        polyline(valueBox, kMeanColour, 2.0f, [&](const RaySample& s) { return valueY(s.runningMean); });
    else
        polyline(valueBox, kMaxColour, 2.0f, [&](const RaySample& s) { return valueY(s.runningMax); });
    polyline(valueBox, kValueColour, 1.6f, [&](const RaySample& s) { return valueY(s.value); });
    if (sampleWidth >= 5.0f)
        for (int m = first; m <= last; ++m) {
            const RaySample& s = profile.samples[m];
            dl->AddCircleFilled(ImVec2(xOf(s.t), valueY(s.value)), 2.2f, kValueColour);
        }
}

// Opacity of each sample as stems (a filled area when they crowd), the
// accumulated opacity as a line, the termination level dashed.
void ProfileCanvas::opacityPlot() const {
    dl->PushClipRect(opacityBox.min, opacityBox.max, true);
    const int limit = profile.stoppedAt >= 0 ? profile.stoppedAt : count - 1;
    for (int m = first; m <= last; ++m) {
        const RaySample& s = profile.samples[m];
        const float x = xOf(s.t);
        const ImU32 col = m <= limit ? kSampleOpacityColour : IM_COL32(150, 90, 90, 110);
        if (sampleWidth >= 4.0f)
            dl->AddLine(ImVec2(x, opacityBox.max.y), ImVec2(x, opacityY(s.classified.a)), col, 2.0f);
        else
            dl->AddRectFilled(ImVec2(x - 0.5f * sampleWidth, opacityY(s.classified.a)),
                              ImVec2(x + 0.5f * sampleWidth + 0.5f, opacityBox.max.y), col);
    }
    if (profile.earlyTermination < 1.0)
        dashedHorizontal(dl, opacityBox.min.x, opacityBox.max.x, opacityY(profile.earlyTermination),
                         IM_COL32(255, 120, 120, 150), em * 0.3f);
    dl->PopClipRect();
    polyline(opacityBox, kAccumulatedColour, 2.2f, [&](const RaySample& s) { return opacityY(s.accumulated.a); });
}

// Colour strips: each sample's own colour, and the pixel so far. Composite:
// each sample's colour at an opacity relative to the most opaque sample of
// the ray, so that transparent samples fade out. Projections: each value as
// the pixel would show it.
void ProfileCanvas::colourStrips() const {
    float peak = 0.0f;
    for (const RaySample& s : profile.samples) peak = std::max(peak, s.classified.a);
    for (const Box* b : {&sampleStrip, &resultStrip}) checkerboard(dl, b->min, b->max, stripHeight * 0.5f);
    for (int m = first; m <= last; ++m) {
        const RaySample& s = profile.samples[m];
        const float x0 = xOf(s.t - 0.5 * profile.step);
        const float x1 = std::max(xOf(s.t + 0.5 * profile.step), x0 + 1.0f);
        const glm::vec4 c = s.classified;
        const float sampleAlpha = composites ? (peak > 0.0f ? c.a / peak : 0.0f) : c.a;
        dl->AddRectFilled(ImVec2(x0, sampleStrip.min.y), ImVec2(x1, sampleStrip.max.y), colourOf(c, sampleAlpha));
        const glm::vec4 acc = s.accumulated;
        const glm::vec4 straight = acc.a > 0.0f ? glm::vec4(glm::vec3(acc) / acc.a, acc.a) : glm::vec4(0.0f);
        dl->AddRectFilled(ImVec2(x0, resultStrip.min.y), ImVec2(x1, resultStrip.max.y), colourOf(straight, acc.a));
    }
    dl->AddRect(sampleStrip.min, sampleStrip.max, kFrameColour);
    dl->AddRect(resultStrip.min, resultStrip.max, kFrameColour);
}

// The stop: samples after it are dimmed, a red line marks it; the sample
// that gives the pixel its value is ringed.
void ProfileCanvas::stopAndChoice() const {
    if (profile.stoppedAt >= 0) {
        const float x = xOf(profile.samples[profile.stoppedAt].t + 0.5 * profile.step);
        if (x < right) dl->AddRectFilled(ImVec2(x, valueBox.min.y), ImVec2(right, bottom), IM_COL32(0, 0, 0, 120));
        const float xs = xOf(profile.model == ProfileModel::Isosurface ? profile.hitT : profile.samples[profile.stoppedAt].t);
        dl->AddLine(ImVec2(xs, valueBox.min.y), ImVec2(xs, bottom), kStopColour, 2.0f);
    }
    if (profile.chosen >= 0 && profile.model != ProfileModel::FirstHit && profile.model != ProfileModel::Isosurface) {
        const RaySample& s = profile.samples[profile.chosen];
        dl->AddCircle(ImVec2(xOf(s.t), valueY(s.value)), em * 0.4f, kMaxColour, 0, 2.0f);
    }
}

void ProfileCanvas::stripLabels() const {
    const char* names[] = {composites ? "colour" : "sample", composites ? "accum." : "pixel"};
    const Box* boxes[] = {&sampleStrip, &resultStrip};
    for (int i = 0; i < 2; ++i) {
        const ImVec2 size = ImGui::CalcTextSize(names[i]);
        dl->AddText(ImVec2(left - size.x - 6.0f, boxes[i]->min.y + 0.5f * (stripHeight - size.y)), kDimLabelColour,
                    names[i]);
    }
}

// Hover: the nearest sample marked, and its numbers in a tooltip.
void ProfileCanvas::hoverSample() const {
    const double t = tLo + (ImGui::GetIO().MousePos.x - left) / (right - left) * (tHi - tLo);
    const int m = std::clamp(int(std::lround((t - profile.tEntry) / profile.step - 0.5)), 0, count - 1);
    const RaySample& s = profile.samples[m];
    const float x = xOf(s.t);
    if (x >= left && x <= right) {
        dl->AddLine(ImVec2(x, valueBox.min.y), ImVec2(x, bottom), kCursorColour, 1.0f);
        dl->AddCircleFilled(ImVec2(x, valueY(s.value)), 3.5f, kValueColour);
        if (composites) dl->AddCircleFilled(ImVec2(x, opacityY(s.accumulated.a)), 3.5f, kAccumulatedColour);
    }
    ImGui::BeginTooltip();
    ImGui::Text("sample %d%s", m, profile.stoppedAt >= 0 && m > profile.stoppedAt ? "  (after the stop)" : "");
    ImGui::Text("t %.4g   at (%.4g, %.4g, %.4g)", s.t, s.position.x, s.position.y, s.position.z);
    ImGui::Text("value %.5g", s.value);
    // The running value the renderer displays (its own, read from its shader).
    if (profile.model == ProfileModel::Maximum) ImGui::TextDisabled("running max %.5g", s.runningMax);
    if (profile.model == ProfileModel::Minimum) ImGui::TextDisabled("running min %.5g", s.runningMin);
    if (profile.model == ProfileModel::Mean) ImGui::TextDisabled("running mean %.5g", s.runningMean);
    if (profile.modelled && profile.model != ProfileModel::Isosurface) {
        const glm::vec4& c = s.classified;
        const glm::vec4& a = s.accumulated;
        if (composites) {
            ImGui::Text("colour %.3f %.3f %.3f   opacity %.4f", c.r, c.g, c.b, c.a);
            ImGui::Text("accumulated C %.3f %.3f %.3f   A %.4f", a.r, a.g, a.b, a.a);
        } else {
            ImGui::Text("shown as %.3f %.3f %.3f   alpha %.3f", c.r, c.g, c.b, c.a);
            ImGui::Text("pixel so far %.3f %.3f %.3f   alpha %.3f", a.r, a.g, a.b, a.a);
        }
    }
    ImGui::EndTooltip();
}

}  // namespace

void RayProfilePanel(const char* label, const RayProfile& profile, const glm::dvec2& valueRange) {
    ImGui::PushID(label);
    const float em = ImGui::GetFontSize();
    const int count = int(profile.samples.size());

    // Header: the pixel, the renderer and the ray's extent.
    ImGui::Text("pixel (%d, %d)  %s", profile.px, profile.py, profile.renderer.c_str());
    if (profile.hitsVolume) {
        ImGui::SameLine();
        ImGui::TextDisabled("  %d samples, step %.3g, t %.4g .. %.4g", count, profile.step, profile.tEntry,
                            profile.tExit);
    }

    const float lineHeight = ImGui::GetTextLineHeightWithSpacing();
    // The footer's lines, and the spacing after the canvas.
    const float footer = lineHeight * (profile.note.empty() ? 2.0f : 3.0f) + ImGui::GetStyle().ItemSpacing.y + 2.0f;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const ImVec2 canvasSize(std::max(avail.x, 24.0f * em), std::max(avail.y - footer, 14.0f * em));
    if (count == 0) {
        ImGui::Dummy(ImVec2(canvasSize.x, em * 0.5f));
        footerLines(profile);
        ImGui::PopID();
        return;
    }

    const ProfileCanvas canvas(profile, canvasSize, valueRange);
    canvas.legend();
    canvas.frames();
    canvas.depthAxis();
    // Everything from here on is clipped to the plots' columns.
    canvas.dl->PushClipRect(ImVec2(canvas.left, canvas.origin.y), ImVec2(canvas.right, canvas.axisY), true);
    canvas.valueLines();
    if (canvas.composites) canvas.opacityPlot();
    if (canvas.strips) canvas.colourStrips();
    canvas.stopAndChoice();
    canvas.dl->PopClipRect();
    if (canvas.strips) canvas.stripLabels();
    if (canvas.hovered && !canvas.active) canvas.hoverSample();

    footerLines(profile);
    ImGui::PopID();
}

}  // namespace voxlab
