// voxlab: the 2D transfer-function editor widget (see transfer_function_editor.h
// for its layout and mouse bindings) and the texture of its histogram.
#include "voxlab_gl.h"  // first: it replaces the system GL headers

#include "voxlab/gl_object.h"
#include "voxlab/transfer_function_editor.h"

#include <imgui.h>
#include <imgui_internal.h>  // SetItemUsingMouseWheel

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "transfer_function_editor_drawing.h"
#include "grey_texture.h"

namespace voxlab {

// ---------------------------------------------------------------------------
// The histogram image and its texture cache.

std::vector<std::uint8_t> histogram2DImage(const Histogram2D& histogram, bool logScale) {
    const std::size_t size =
        std::size_t(std::max(histogram.valueBins, 0)) * std::size_t(std::max(histogram.gradientBins, 0));
    std::vector<std::uint8_t> image(size, 0);
    if (histogram.counts.size() != size || size == 0) return image;
    const std::uint64_t largest = *std::max_element(histogram.counts.begin(), histogram.counts.end());
    if (largest == 0) return image;
    const auto scaled = [&](std::uint64_t c) { return logScale ? std::log1p(double(c)) : double(c); };
    const double top = scaled(largest);
    for (std::size_t i = 0; i < size; ++i)
        image[i] = std::uint8_t(std::lround(255.0 * scaled(histogram.counts[i]) / top));
    return image;
}

namespace {

struct CachedTexture {
    const Histogram2D* address = nullptr;
    int valueBins = 0, gradientBins = 0;
    bool logScale = true;
    std::uint64_t contents = 0;  // a hash of the counts: a histogram recomputed in place is uploaded again
    GlTexture texture;
    std::uint64_t lastUse = 0;
};

std::vector<CachedTexture>& textureCache() {
    static std::vector<CachedTexture> cache;
    return cache;
}

constexpr std::size_t kMaxCachedTextures = 4;

// FNV-1a over the counts and the ranges (64-bit offset basis and prime from
// the published FNV parameters).
std::uint64_t contentsHash(const Histogram2D& h) {
    std::uint64_t hash = 14695981039346656037ull;
    const auto mix = [&](const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
    };
    mix(h.counts.data(), h.counts.size() * sizeof(std::uint64_t));
    mix(&h.valueLo, sizeof h.valueLo), mix(&h.valueHi, sizeof h.valueHi), mix(&h.gradientMax, sizeof h.gradientMax);
    return hash;
}

#ifdef __EMSCRIPTEN__
bool glAvailable() { return true; }  // WebGL 2's functions are linked, never loaded
#else
bool glAvailable() { return voxlab_gl.GenTextures && voxlab_gl.TexImage2D && voxlab_gl.GetIntegerv; }
#endif

void upload(GLuint texture, const Histogram2D& histogram, bool logScale) {
    const std::vector<std::uint8_t> image = histogram2DImage(histogram, logScale);
    GLint boundTexture = 0, unpackBuffer = 0, alignment = 4, rowLength = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &boundTexture);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpackBuffer);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &rowLength);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glBindTexture(GL_TEXTURE_2D, texture);
    // Shown as white with the count as coverage: it blends over the frame.
    viewer::uploadGreyTexture(histogram.valueBins, histogram.gradientBins, image.data(), viewer::GreyAs::Coverage);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, GLuint(boundTexture));
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, rowLength);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpackBuffer));
}

}  // namespace

unsigned histogram2DTexture(const Histogram2D& histogram, bool logScale) {
    if (!glAvailable() || histogram.valueBins <= 0 || histogram.gradientBins <= 0 ||
        histogram.counts.size() != std::size_t(histogram.valueBins) * std::size_t(histogram.gradientBins))
        return 0;
    static std::uint64_t clock = 0;
    auto& cache = textureCache();
    const std::uint64_t contents = contentsHash(histogram);
    for (CachedTexture& entry : cache) {
        if (entry.address != &histogram || entry.logScale != logScale) continue;
        if (entry.valueBins != histogram.valueBins || entry.gradientBins != histogram.gradientBins ||
            entry.contents != contents) {
            upload(entry.texture, histogram, logScale);
            entry.valueBins = histogram.valueBins, entry.gradientBins = histogram.gradientBins;
            entry.contents = contents;
        }
        entry.lastUse = ++clock;
        return entry.texture;
    }
    if (cache.size() >= kMaxCachedTextures) {
        auto oldest = std::min_element(cache.begin(), cache.end(),
                                       [](const auto& a, const auto& b) { return a.lastUse < b.lastUse; });
        cache.erase(oldest);
    }
    CachedTexture entry;
    entry.address = &histogram, entry.valueBins = histogram.valueBins, entry.gradientBins = histogram.gradientBins;
    entry.logScale = logScale, entry.contents = contents, entry.lastUse = ++clock;
    entry.texture = GlTexture::make();
    upload(entry.texture, histogram, logScale);
    cache.push_back(std::move(entry));
    return cache.back().texture;
}

void releaseTransferFunctionEditorTextures() {
    auto& cache = textureCache();
    if (!glAvailable())  // the context is gone, and its objects with it
        for (CachedTexture& entry : cache) entry.texture.release();
    cache.clear();
}

// ---------------------------------------------------------------------------
// The editor.

namespace {

using namespace tf_editor;

// Screen <-> data inside the plot: x linear in value over [vlo, vhi], y
// linear in gradient magnitude, 0 at the bottom edge and `top` at the top:
// gmax (the histogram's largest gradient, the domain's end) unless zoomed.
struct Plot {
    ImVec2 min, max;
    double vlo, vhi, gmax, top;

    double width() const { return double(max.x) - double(min.x); }
    double height() const { return double(max.y) - double(min.y); }
    float xOf(double v) const { return float(min.x + (v - vlo) / (vhi - vlo) * width()); }
    float yOf(double g) const { return float(max.y - g / top * height()); }
    double valueAt(float x) const { return vlo + (double(x) - min.x) / width() * (vhi - vlo); }
    double gradientAt(float y) const { return (double(max.y) - y) / height() * top; }
    ImVec2 clamped(ImVec2 p) const { return ImVec2(std::clamp(p.x, min.x, max.x), std::clamp(p.y, min.y, max.y)); }
    // The smallest radius a triangle keeps (a thousandth of the range wide at the top).
    double minRadius() const { return 1e-3 * (vhi - vlo) / top; }
};
constexpr float kMaxZoom = 64.0f;

// What a press grabs: a widget's inside (move), a triangle's top corner
// (radius) or a box's corner (resize; corners 0..3 are (v0,g0), (v1,g0),
// (v1,g1), (v0,g1)).
enum class Grip { None, Move, Radius, Corner };

struct Hit {
    int widget = -1;
    Grip grip = Grip::None;
    int corner = -1;
};

struct Handle {
    ImVec2 position;
    Hit hit;
    double gradient = 0.0;  // a triangle's radius handle: the gradient magnitude it sits at
};

// Where an edge of a triangle leaves the plot: at the top, or at the side it
// reaches first (value fv + side * r * g hits vlo or vhi).
double edgeExit(const Tf2dWidget& w, const Plot& plot, int side) {
    const double room = side > 0 ? plot.vhi - w.valueRange.x : w.valueRange.x - plot.vlo;
    return std::clamp(room / w.radius, 0.0, plot.top);
}

std::vector<Handle> handlesOf(const Tf2dWidget& w, int index, const Plot& plot) {
    std::vector<Handle> out;
    if (w.kind == Tf2dWidget::Kind::Triangle) {
        const double fv = w.valueRange.x;
        out.push_back({plot.clamped(ImVec2(plot.xOf(fv), plot.max.y)), {index, Grip::Move, -1}});
        for (int side : {-1, 1}) {
            // A handle needs some height to set a radius by: at least a tenth of the plot.
            const double g = std::max(edgeExit(w, plot, side), 0.1 * plot.top);
            out.push_back({plot.clamped(ImVec2(plot.xOf(fv + side * w.radius * g), plot.yOf(g))),
                           {index, Grip::Radius, side > 0 ? 1 : 0}, g});
        }
    } else {
        const glm::dvec2 v = w.valueRange, g = w.gradientRange;
        const double cornerValue[4] = {v.x, v.y, v.y, v.x}, cornerGradient[4] = {g.x, g.x, g.y, g.y};
        for (int k = 0; k < 4; ++k)
            out.push_back({plot.clamped(ImVec2(plot.xOf(cornerValue[k]), plot.yOf(cornerGradient[k]))),
                           {index, Grip::Corner, k}});
    }
    return out;
}

bool inside(const Tf2dWidget& w, double f, double g) {
    if (w.kind == Tf2dWidget::Kind::Box)
        return f >= w.valueRange.x && f <= w.valueRange.y && g >= w.gradientRange.x && g <= w.gradientRange.y;
    return g > 0.0 && std::abs(f - w.valueRange.x) <= w.radius * g;
}

// The drawing order puts the selected widget on top, then the list's last;
// hits are searched in the reverse order. Handles win over insides.
std::vector<int> topFirst(int count, int selected) {
    std::vector<int> order;
    if (selected >= 0 && selected < count) order.push_back(selected);
    for (int i = count - 1; i >= 0; --i)
        if (i != selected) order.push_back(i);
    return order;
}

Hit hitTest(const std::vector<Tf2dWidget>& widgets, const Plot& plot, ImVec2 mouse, int selected) {
    const std::vector<int> order = topFirst(int(widgets.size()), selected);
    Hit best;
    float bestDistance = kHitRadius * kHitRadius;
    for (int i : order)
        for (const Handle& h : handlesOf(widgets[std::size_t(i)], i, plot)) {
            const float d = distanceSquared(h.position, mouse);
            if (d < bestDistance) best = h.hit, bestDistance = d;
        }
    if (best.widget >= 0) return best;
    const double f = plot.valueAt(mouse.x), g = plot.gradientAt(mouse.y);
    for (int i : order)
        if (inside(widgets[std::size_t(i)], f, g)) return {i, Grip::Move, -1};
    return {};
}

struct Drag {
    Hit hit;
    ImVec2 grabOffset{0, 0};  // press position minus the grabbed handle
    ImVec2 press{0, 0};
    ImVec2 lastMouse{0, 0};
    Tf2dWidget original;
    double handleGradient = 0.0;  // a radius handle's height, kept while dragging
};

struct EditorState {
    Drag drag;
    glm::dvec2 popupAt{0.0};  // where the "add" menu was opened, in data units
    float zoom = 1.0f;        // of the gradient axis (the wheel): the plot's top is gmax / zoom
    std::uint64_t clickStamp = 0;  // see clickClock()
};

// The widget as the drag has it now, from its state at the press.
Tf2dWidget dragged(const Drag& drag, const Plot& plot, ImVec2 mouse) {
    Tf2dWidget w = drag.original;
    const ImVec2 target(mouse.x - drag.grabOffset.x, mouse.y - drag.grabOffset.y);
    switch (drag.hit.grip) {
    case Grip::Move: {
        const double df = plot.valueAt(mouse.x) - plot.valueAt(drag.press.x);
        const double dg = plot.gradientAt(mouse.y) - plot.gradientAt(drag.press.y);
        if (w.kind == Tf2dWidget::Kind::Triangle) {
            w.valueRange = glm::dvec2(std::clamp(w.valueRange.x + df, plot.vlo, plot.vhi));
        } else {
            // Shifted as a whole and kept inside the domain (one already
            // sticking out may not go further out).
            const double sf =
                std::clamp(df, std::min(plot.vlo - w.valueRange.x, 0.0), std::max(plot.vhi - w.valueRange.y, 0.0));
            const double sg =
                std::clamp(dg, std::min(-w.gradientRange.x, 0.0), std::max(plot.gmax - w.gradientRange.y, 0.0));
            w.valueRange += sf, w.gradientRange += sg;
        }
        break;
    }
    case Grip::Radius:
        // The edge passes through the handle, which follows the mouse sideways.
        w.radius = std::max(plot.minRadius(), std::abs(plot.valueAt(target.x) - w.valueRange.x) / drag.handleGradient);
        break;
    case Grip::Corner: {
        const double f = std::clamp(plot.valueAt(target.x), plot.vlo, plot.vhi);
        const double g = std::clamp(plot.gradientAt(target.y), 0.0, plot.gmax);
        const int k = drag.hit.corner;
        if (k == 0 || k == 3) w.valueRange.x = std::min(f, w.valueRange.y);
        else w.valueRange.y = std::max(f, w.valueRange.x);
        if (k == 0 || k == 1) w.gradientRange.x = std::min(g, w.gradientRange.y);
        else w.gradientRange.y = std::max(g, w.gradientRange.x);
        break;
    }
    case Grip::None:
        break;
    }
    return w;
}

glm::vec3 paletteColour(std::size_t n) {
    static const glm::vec3 palette[] = {{1.00f, 0.86f, 0.62f}, {0.90f, 0.45f, 0.30f}, {0.40f, 0.72f, 0.32f},
                                        {0.38f, 0.58f, 0.95f}, {0.95f, 0.80f, 0.30f}, {0.78f, 0.42f, 0.80f}};
    return palette[n % (sizeof palette / sizeof palette[0])];
}

Tf2dWidget newTriangle(double f, const Plot& plot, std::size_t count) {
    Tf2dWidget w;
    w.kind = Tf2dWidget::Kind::Triangle;
    w.valueRange = glm::dvec2(std::clamp(f, plot.vlo, plot.vhi));
    w.radius = 0.04 * (plot.vhi - plot.vlo) / plot.top;  // 8% of the range wide at the plot's top
    w.alpha = 0.6f;
    w.color = paletteColour(count);
    return w;
}

Tf2dWidget newBox(double f, double g, const Plot& plot, std::size_t count) {
    Tf2dWidget w;
    w.kind = Tf2dWidget::Kind::Box;
    const double halfValue = 0.06 * (plot.vhi - plot.vlo), halfGradient = 0.15 * plot.top;
    const double fc = std::clamp(f, plot.vlo + halfValue, plot.vhi - halfValue);
    const double gc = std::clamp(g, halfGradient, plot.top - halfGradient);
    w.valueRange = {fc - halfValue, fc + halfValue};
    w.gradientRange = {gc - halfGradient, gc + halfGradient};
    w.alpha = 0.25f;
    w.color = paletteColour(count);
    return w;
}

// The histogram: a texture through the OpenGL3 backend, else (headless, or
// another renderer) a coarse grid of rectangles with the same shading.
void drawHistogram(ImDrawList* draw, const Plot& plot, const Histogram2D& histogram, bool logScale) {
    constexpr ImU32 tint = IM_COL32(200, 215, 255, 200);
    const char* backend = ImGui::GetIO().BackendRendererName;
    if (backend && std::strncmp(backend, "imgui_impl_opengl3", 18) == 0) {
        if (const unsigned texture = histogram2DTexture(histogram, logScale)) {
            // Row 0 (gradient 0) at the bottom; the plot shows the rows up to its top.
            const float v = float(std::min(1.0, plot.top / plot.gmax));
            draw->AddImage(ImTextureID(std::intptr_t(texture)), plot.min, plot.max, ImVec2(0, v), ImVec2(1, 0), tint);
            return;
        }
    }
    const std::vector<std::uint8_t> image = histogram2DImage(histogram, logScale);
    if (image.empty()) return;
    const int nx = histogram.valueBins, ny = histogram.gradientBins;
    const int stepX = std::max(1, (nx + 95) / 96), stepY = std::max(1, (ny + 47) / 48);
    for (int y0 = 0; y0 < ny; y0 += stepY)
        for (int x0 = 0; x0 < nx; x0 += stepX) {
            int level = 0;
            for (int y = y0; y < std::min(ny, y0 + stepY); ++y)
                for (int x = x0; x < std::min(nx, x0 + stepX); ++x)
                    level = std::max(level, int(image[std::size_t(y) * std::size_t(nx) + std::size_t(x)]));
            if (level == 0) continue;
            const float x1 = plot.min.x + float(plot.width() * x0 / nx);
            const float x2 = plot.min.x + float(plot.width() * std::min(nx, x0 + stepX) / nx);
            const float y1 = plot.yOf(plot.gmax * std::min(ny, y0 + stepY) / ny);
            const float y2 = plot.yOf(plot.gmax * y0 / ny);
            if (y2 < plot.min.y) continue;
            draw->AddRectFilled(ImVec2(x1, y1), ImVec2(x2, y2), IM_COL32(200, 215, 255, 200 * level / 255));
        }
}

void drawWidget(ImDrawList* draw, const Plot& plot, const Tf2dWidget& w, bool selected) {
    const float fill = 0.08f + 0.4f * std::clamp(w.alpha, 0.0f, 1.0f);
    const glm::vec3 edge = glm::mix(w.color, glm::vec3(1.0f), 0.35f);
    const float thickness = selected ? 2.5f : 1.5f;
    if (w.kind == Tf2dWidget::Kind::Triangle) {
        // Levoy's opacity falls linearly from the centre line to the edges at
        // every height, exactly what Gouraud shading does across these two.
        const double fv = w.valueRange.x, half = w.radius * plot.top;
        const ImVec2 apex(plot.xOf(fv), plot.max.y), top(plot.xOf(fv), plot.min.y);
        const ImVec2 left(plot.xOf(fv - half), plot.min.y), right(plot.xOf(fv + half), plot.min.y);
        const ImU32 centre = colour(w.color, fill), outer = colour(w.color, 0.0f);
        fillTriangle(draw, apex, top, left, centre, centre, outer);
        fillTriangle(draw, apex, right, top, centre, outer, centre);
        draw->AddLine(apex, top, colour(edge, 0.35f), 1.0f);
        for (const ImVec2& end : {left, right}) {
            draw->AddLine(apex, end, IM_COL32(10, 10, 15, 150), thickness + 2.0f);
            draw->AddLine(apex, end, selected ? highlightColour() : colour(edge, 1.0f), thickness);
        }
    } else {
        const ImVec2 a(plot.xOf(w.valueRange.x), plot.yOf(w.gradientRange.y));
        const ImVec2 b(plot.xOf(w.valueRange.y), plot.yOf(w.gradientRange.x));
        draw->AddRectFilled(a, b, colour(w.color, fill * 0.8f));
        draw->AddRect(a, b, IM_COL32(10, 10, 15, 150), 0.0f, 0, thickness + 2.0f);
        draw->AddRect(a, b, selected ? highlightColour() : colour(edge, 1.0f), 0.0f, 0, thickness);
    }
}

const char* kindName(const Tf2dWidget& w) { return w.kind == Tf2dWidget::Kind::Triangle ? "triangle" : "box"; }

void widgetTooltip(const Tf2dWidget& w, int index) {
    ImGui::BeginTooltip();
    ImGui::TextDisabled("%s %d", kindName(w), index + 1);
    if (w.kind == Tf2dWidget::Kind::Triangle) {
        ImGui::Text("value     %s", formatValue(w.valueRange.x).c_str());
        ImGui::Text("radius    %s", formatValue(w.radius).c_str());
    } else {
        ImGui::Text("value     %s .. %s", formatValue(w.valueRange.x).c_str(), formatValue(w.valueRange.y).c_str());
        ImGui::Text("gradient  %s .. %s", formatValue(w.gradientRange.x).c_str(),
                    formatValue(w.gradientRange.y).c_str());
    }
    ImGui::Text("opacity   %.3f", w.alpha);
    ImGui::EndTooltip();
}

std::uint64_t countAt(const Histogram2D& h, double f, double g) {
    if (h.valueBins <= 0 || h.gradientBins <= 0 || !(h.valueHi > h.valueLo) || !(h.gradientMax > 0.0)) return 0;
    if (h.counts.size() != std::size_t(h.valueBins) * std::size_t(h.gradientBins)) return 0;
    const int x = std::clamp(int((f - h.valueLo) / (h.valueHi - h.valueLo) * h.valueBins), 0, h.valueBins - 1);
    const int y = std::clamp(int(g / h.gradientMax * h.gradientBins), 0, h.gradientBins - 1);
    return h.counts[std::size_t(y) * std::size_t(h.valueBins) + std::size_t(x)];
}

// One frame of the editor: what its parts below share.
struct Frame2D {
    std::vector<Tf2dWidget>& widgets;
    int* selected;
    EditorState& state;
    const Plot& plot;
    ImVec2 mouse;
    Hit hit;            // what the mouse is over (none while dragging)
    bool hovered, active;
    double vlo, vhi, gmax;
    bool room() const { return int(widgets.size()) < kMaxTf2dWidgets; }  // for one more widget
};

void addWidget(Frame2D& f, const Tf2dWidget& w) {
    f.widgets.push_back(w);
    *f.selected = int(f.widgets.size()) - 1;
}

// The left button: a click selects and starts a drag (a double click on
// nothing adds a triangle, held for moving); moving the mouse drags.
bool leftButton(Frame2D& f) {
    Drag& drag = f.state.drag;
    bool changed = false;
    if (f.hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
        f.state.clickStamp = ++clickClock();
        *f.selected = f.hit.widget;
        if (f.hit.widget >= 0) {
            ImVec2 at = f.mouse;
            double handleGradient = 0.0;
            if (f.hit.grip != Grip::Move)
                for (const Handle& h : handlesOf(f.widgets[std::size_t(f.hit.widget)], f.hit.widget, f.plot))
                    if (h.hit.grip == f.hit.grip && h.hit.corner == f.hit.corner)
                        at = h.position, handleGradient = h.gradient;
            drag = {f.hit, ImVec2(f.mouse.x - at.x, f.mouse.y - at.y), f.mouse, f.mouse,
                    f.widgets[std::size_t(f.hit.widget)], handleGradient};
        } else if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && f.room()) {
            addWidget(f, newTriangle(f.plot.valueAt(f.mouse.x), f.plot, f.widgets.size()));
            drag = {{*f.selected, Grip::Move, -1}, ImVec2(0, 0), f.mouse, f.mouse, f.widgets.back(), 0.0};
            changed = true;
        }
    } else if (f.active && drag.hit.widget >= 0 && ImGui::IsMouseDown(ImGuiMouseButton_Left) &&
               (f.mouse.x != drag.lastMouse.x || f.mouse.y != drag.lastMouse.y)) {
        const Tf2dWidget w = dragged(drag, f.plot, f.mouse);
        Tf2dWidget& target = f.widgets[std::size_t(drag.hit.widget)];
        if (!(w == target)) target = w, changed = true;
        drag.lastMouse = f.mouse;
    }
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) drag.hit = {};
    return changed;
}

// A right click removes the widget under the mouse, or offers new ones
// there; Delete removes the selected one (if the last click was here).
bool rightButtonAndDelete(Frame2D& f) {
    const Drag& drag = f.state.drag;
    int remove = -1;
    if (f.hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && drag.hit.widget < 0) {
        f.state.clickStamp = ++clickClock();
        if (f.hit.widget >= 0) {
            remove = f.hit.widget;
        } else {
            f.state.popupAt = {f.plot.valueAt(f.mouse.x), f.plot.gradientAt(f.mouse.y)};
            ImGui::OpenPopup("##add");
        }
    }
    if (remove < 0 && *f.selected >= 0 && drag.hit.widget < 0 && f.state.clickStamp == clickClock() &&
        deletePressed())
        remove = *f.selected;
    bool changed = false;
    if (remove >= 0) {
        f.widgets.erase(f.widgets.begin() + remove);
        if (*f.selected == remove) *f.selected = -1;
        else if (*f.selected > remove) --*f.selected;
        changed = true;
    }
    if (ImGui::BeginPopup("##add")) {
        ImGui::TextDisabled("at value %s", formatValue(f.state.popupAt.x).c_str());
        ImGui::BeginDisabled(!f.room());
        if (ImGui::MenuItem("add a triangle here"))
            addWidget(f, newTriangle(f.state.popupAt.x, f.plot, f.widgets.size())), changed = true;
        if (ImGui::MenuItem("add a box here"))
            addWidget(f, newBox(f.state.popupAt.x, f.state.popupAt.y, f.plot, f.widgets.size())), changed = true;
        ImGui::EndDisabled();
        ImGui::EndPopup();
    }
    return changed;
}

// The frame, the histogram, the widgets (the selected on top), the
// crosshair, the gradient axis's top and the handles.
void drawPlot(const Frame2D& f, const EditorFrame& frame, const Histogram2D& histogram, bool logHistogram) {
    const Plot& plot = f.plot;
    const float rounding = ImGui::GetStyle().FrameRounding;
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(frame.origin, frame.max, styleColour(ImGuiCol_FrameBg), rounding);
    draw->PushClipRect(plot.min, plot.max, true);
    drawHistogram(draw, plot, histogram, logHistogram);
    const std::vector<int> order = topFirst(int(f.widgets.size()), *f.selected);
    for (auto it = order.rbegin(); it != order.rend(); ++it)
        drawWidget(draw, plot, f.widgets[std::size_t(*it)], *it == *f.selected);
    if (f.hovered && f.hit.widget < 0 && f.state.drag.hit.widget < 0) {
        const ImU32 cross = styleColour(ImGuiCol_Text, 0.25f);
        draw->AddLine(ImVec2(f.mouse.x, plot.min.y), ImVec2(f.mouse.x, plot.max.y), cross);
        draw->AddLine(ImVec2(plot.min.x, f.mouse.y), ImVec2(plot.max.x, f.mouse.y), cross);
    }
    draw->PopClipRect();
    // The gradient magnitude at the top: the largest, or the zoomed axis's top, highlighted.
    const std::string top = "gradient " + formatValue(plot.top);
    drawLabel(draw, ImVec2(plot.min.x + 3.0f, plot.min.y + 1.0f), top.c_str(),
              f.state.zoom > 1.0f ? highlightColour() : styleColour(ImGuiCol_TextDisabled));
    draw->PushClipRect(frame.origin, frame.max, true);
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
        const Tf2dWidget& w = f.widgets[std::size_t(*it)];
        for (const Handle& h : handlesOf(w, *it, plot)) {
            const bool isHovered = f.hit.widget == *it && f.hit.grip == h.hit.grip && f.hit.corner == h.hit.corner;
            drawHandle(draw, h.position, colour(w.color, 1.0f), *it == *f.selected, isHovered);
        }
    }
    draw->PopClipRect();
    draw->AddRect(frame.origin, frame.max, styleColour(ImGuiCol_Border), rounding);
}

// The widget dragged or under the mouse, or what lies under it.
void hoverTooltip(const Frame2D& f, const Histogram2D& histogram, const TransferFunction2D& tf) {
    const Drag& drag = f.state.drag;
    if (drag.hit.widget >= 0 && f.active) {
        widgetTooltip(f.widgets[std::size_t(drag.hit.widget)], drag.hit.widget);
    } else if (f.hovered && f.hit.widget >= 0) {
        widgetTooltip(f.widgets[std::size_t(f.hit.widget)], f.hit.widget);
    } else if (f.hovered) {
        const double value = std::clamp(f.plot.valueAt(f.mouse.x), f.vlo, f.vhi);
        const double g = std::clamp(f.plot.gradientAt(f.mouse.y), 0.0, f.plot.top);
        ImGui::BeginTooltip();
        ImGui::Text("value     %s", formatValue(value).c_str());
        ImGui::Text("gradient  %s", formatValue(g).c_str());
        ImGui::TextDisabled("voxels    %llu", (unsigned long long)countAt(histogram, value, g));
        ImGui::TextDisabled("function opacity %.3f", tf.evaluate(value, g).a);
        ImGui::TextDisabled("double-click: add a triangle");
        ImGui::EndTooltip();
    }
}

// The value axis's ends, with the label between them.
void valueAxis(const Frame2D& f, const EditorFrame& frame, const char* label) {
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const float y = ImGui::GetCursorScreenPos().y;
    const std::string loText = formatValue(f.vlo), hiText = formatValue(f.vhi), title = visibleLabel(label);
    const ImU32 text = styleColour(ImGuiCol_TextDisabled);
    draw->AddText(ImVec2(f.plot.min.x, y), text, loText.c_str());
    draw->AddText(ImVec2(f.plot.max.x - ImGui::CalcTextSize(hiText.c_str()).x, y), text, hiText.c_str());
    const std::string middle = title.empty() ? "value" : title;
    draw->AddText(ImVec2(frame.origin.x + (frame.width - ImGui::CalcTextSize(middle.c_str()).x) * 0.5f, y),
                  title.empty() ? text : styleColour(ImGuiCol_Text), middle.c_str());
    ImGui::Dummy(ImVec2(frame.width, ImGui::GetTextLineHeight()));
}

// A triangle's value and radius, or a box's value and gradient ranges.
bool shapeFields(const Frame2D& f, Tf2dWidget& w) {
    const ImGuiStyle& style = ImGui::GetStyle();
    const double vlo = f.vlo, vhi = f.vhi, gmax = f.gmax;
    const float speed = float((vhi - vlo) / 1000.0);
    const float half = (ImGui::GetContentRegionAvail().x - style.ItemSpacing.x) * 0.5f;
    bool changed = false;
    ImGui::SetNextItemWidth(half);
    if (w.kind == Tf2dWidget::Kind::Triangle) {
        double value = w.valueRange.x;
        if (ImGui::DragScalar("##value", ImGuiDataType_Double, &value, speed, &vlo, &vhi, "value %.5g",
                              ImGuiSliderFlags_AlwaysClamp) &&
            value != w.valueRange.x)
            w.valueRange = glm::dvec2(std::clamp(value, vlo, vhi)), changed = true;
        ImGui::SameLine();
        ImGui::SetNextItemWidth(half);
        double radius = w.radius;
        const double rMin = f.plot.minRadius(), rMax = 2.0 * (vhi - vlo) / f.plot.top;
        if (ImGui::DragScalar("##radius", ImGuiDataType_Double, &radius, float(rMax / 2000.0), &rMin, &rMax,
                              "radius %.4g", ImGuiSliderFlags_AlwaysClamp) &&
            radius != w.radius)
            w.radius = std::clamp(radius, rMin, rMax), changed = true;
        return changed;
    }
    double v[2] = {w.valueRange.x, w.valueRange.y};
    if (ImGui::DragScalarN("##value", ImGuiDataType_Double, v, 2, speed, &vlo, &vhi, "value %.5g",
                           ImGuiSliderFlags_AlwaysClamp))
        w.valueRange = {std::min(v[0], v[1]), std::max(v[0], v[1])}, changed = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("value range");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(half);
    double g[2] = {w.gradientRange.x, w.gradientRange.y};
    const double gLo = 0.0;
    if (ImGui::DragScalarN("##gradient", ImGuiDataType_Double, g, 2, float(gmax / 1000.0), &gLo, &gmax,
                           "gradient %.4g", ImGuiSliderFlags_AlwaysClamp))
        w.gradientRange = {std::min(g[0], g[1]), std::max(g[0], g[1])}, changed = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("gradient magnitude range");
    return changed;
}

// The selected widget's colour, opacity, delete button and shape.
bool selectedWidgetControls(Frame2D& f) {
    const ImGuiStyle& style = ImGui::GetStyle();
    ImGui::PushID("##widget");
    Tf2dWidget& w = f.widgets[std::size_t(*f.selected)];
    bool changed = false;
    float rgb[3] = {w.color.r, w.color.g, w.color.b};
    if (ImGui::ColorEdit3("##colour", rgb, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_NoLabel))
        w.color = glm::clamp(glm::vec3(rgb[0], rgb[1], rgb[2]), 0.0f, 1.0f), changed = true;
    ImGui::SameLine();
    const float deleteWidth = ImGui::CalcTextSize("delete").x + 2.0f * style.FramePadding.x;
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - deleteWidth - style.ItemSpacing.x);
    float alpha = w.alpha;
    if (ImGui::SliderFloat("##opacity", &alpha, 0.0f, 1.0f, "opacity %.3f", ImGuiSliderFlags_AlwaysClamp) &&
        alpha != w.alpha)
        w.alpha = std::clamp(alpha, 0.0f, 1.0f), changed = true;
    ImGui::SameLine();
    const bool erase = ImGui::Button("delete");
    changed |= shapeFields(f, w);
    if (erase) {
        f.widgets.erase(f.widgets.begin() + *f.selected);
        *f.selected = -1;
        changed = true;
    }
    ImGui::PopID();
    return changed;
}

// The buttons that add widgets, and the selected widget's fields.
bool widgetControls(Frame2D& f) {
    bool changed = false;
    ImGui::BeginDisabled(!f.room());
    if (ImGui::Button("+ triangle"))
        addWidget(f, newTriangle(0.5 * (f.vlo + f.vhi), f.plot, f.widgets.size())), changed = true;
    ImGui::SameLine();
    if (ImGui::Button("+ box"))
        addWidget(f, newBox(0.5 * (f.vlo + f.vhi), 0.5 * f.plot.top, f.plot, f.widgets.size())), changed = true;
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextDisabled("%d of %d widgets", int(f.widgets.size()), kMaxTf2dWidgets);
    if (*f.selected >= 0)
        changed |= selectedWidgetControls(f);
    else
        ImGui::TextDisabled("double-click: add   drag: move, resize   right-click: delete   wheel: zoom");
    return changed;
}

}  // namespace

bool TransferFunction2DEditor(const char* label, TransferFunction2D* tf, const Histogram2D& histogram, int* selected,
                              const TransferFunction2DEditorOptions& options) {
    ImGui::PushID(label);
    const ImGuiID id = ImGui::GetID("##editor");
    if (!selected) selected = ImGui::GetStateStorage()->GetIntRef(ImGui::GetID("##selected"), -1);
    std::vector<Tf2dWidget>& widgets = tf->widgets();
    if (*selected >= int(widgets.size()) || *selected < -1) *selected = -1;

    double vlo = histogram.valueLo, vhi = histogram.valueHi, gmax = histogram.gradientMax;
    if (!(std::isfinite(vlo) && std::isfinite(vhi))) vlo = 0.0, vhi = 1.0;
    if (!(vhi > vlo)) vhi = vlo + 1.0;
    if (!(std::isfinite(gmax) && gmax > 0.0)) gmax = 1.0;
    EditorState& state = persistentState<EditorState>(id);
    const EditorFrame frame = editorFrame(options.height, &state.zoom, kMaxZoom);
    const Plot plot{frame.plotMin(), frame.plotMax(), vlo, vhi, gmax, gmax / double(state.zoom)};
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    if (state.drag.hit.widget >= int(widgets.size())) state.drag.hit = {};
    const Hit hit = frame.hovered && state.drag.hit.widget < 0 ? hitTest(widgets, plot, mouse, *selected) : Hit{};
    Frame2D f{widgets, selected, state, plot, mouse, hit, frame.hovered, frame.active, vlo, vhi, gmax};

    bool changed = leftButton(f);
    changed |= rightButtonAndDelete(f);
    drawPlot(f, frame, histogram, options.logHistogram);
    hoverTooltip(f, histogram, *tf);
    valueAxis(f, frame, label);
    if (options.showWidgetControls) changed |= widgetControls(f);
    ImGui::PopID();
    return changed;
}

}  // namespace voxlab
