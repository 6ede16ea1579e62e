// voxlab: the 1D transfer-function editor widget (see transfer_function_editor.h
// for its layout and mouse bindings).
#include "voxlab/transfer_function_editor.h"

#include <imgui.h>
#include <imgui_internal.h>  // SetItemUsingMouseWheel

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "transfer_function_editor_drawing.h"

namespace voxlab {

namespace {

using namespace tf_editor;

// The point being dragged (index into the sorted points), where it was
// grabbed relative to its handle, and the mouse position last applied (a
// drag only writes the function when the mouse moved).
struct Drag {
    int point = -1;
    ImVec2 grabOffset{0, 0};
    ImVec2 lastMouse{0, 0};
};

// Per editor: the drag, and the opacity axis's zoom (the wheel over the
// plot; the top of the plot is opacity 1 / zoom, for the small opacities
// that thick materials need).
struct EditorState {
    Drag drag;
    float zoom = 1.0f;
    std::uint64_t clickStamp = 0;  // see clickClock()
};
constexpr float kMaxZoom = 32.0f;

// Screen <-> data inside the plot: x linear in value over [lo, hi], y linear
// in opacity, 0 at the bottom edge and `top` (1 unless zoomed) at the top.
struct Plot {
    ImVec2 min, max;
    double lo, hi;
    double top = 1.0;

    double width() const { return double(max.x) - double(min.x); }
    double height() const { return double(max.y) - double(min.y); }
    float xOf(double value) const { return float(min.x + (value - lo) / (hi - lo) * width()); }
    float yOf(double alpha) const { return float(max.y - alpha / top * height()); }
    double valueAt(float x) const { return lo + (double(x) - min.x) / width() * (hi - lo); }
    double alphaAt(float y) const { return (double(max.y) - y) / height() * top; }
    // A point's handle; points outside the plot sit on its edges.
    ImVec2 handle(const ControlPoint& p) const {
        return ImVec2(std::clamp(xOf(p.value), min.x, max.x), yOf(std::clamp(double(p.alpha), 0.0, top)));
    }
};

double snapValue(double v, const Plot& plot, double snap) {
    if (snap > 0.0) v = std::round(v / snap) * snap;
    return std::clamp(v, plot.lo, plot.hi);
}

// The handle nearest to `mouse` within the hit radius, or -1.
int handleAt(const std::vector<ControlPoint>& points, const Plot& plot, ImVec2 mouse) {
    int best = -1;
    float bestDistance = kHitRadius * kHitRadius;
    for (int i = 0; i < int(points.size()); ++i) {
        const float d = distanceSquared(plot.handle(points[i]), mouse);
        if (d <= bestDistance) best = i, bestDistance = d;
    }
    return best;
}

// After points[index].value changed, moves the point to its place in value
// order (past neighbours it overtook; equal values keep their order) and
// returns its new index.
int resort(std::vector<ControlPoint>& points, int index) {
    while (index > 0 && points[index - 1].value > points[index].value)
        std::swap(points[index - 1], points[index]), --index;
    while (index + 1 < int(points.size()) && points[index + 1].value < points[index].value)
        std::swap(points[index + 1], points[index]), ++index;
    return index;
}

// The function between its points, clipped to the plot's range: pieces
// (value, colour, opacity) -> (value, colour, opacity) over which both are
// linear, constant beyond the first and last point.
struct Node {
    double value;
    glm::vec3 color;
    float alpha;
};

Node lerp(const Node& a, const Node& b, double value) {
    const double t = b.value > a.value ? (value - a.value) / (b.value - a.value) : 0.0;
    return {value, glm::mix(a.color, b.color, float(t)), float(a.alpha + (b.alpha - a.alpha) * t)};
}

std::vector<std::pair<Node, Node>> pieces(const std::vector<ControlPoint>& points, double lo, double hi) {
    std::vector<Node> nodes;
    if (points.empty()) return {};
    if (points.front().value > lo) nodes.push_back({lo, points.front().color, points.front().alpha});
    for (const ControlPoint& p : points) nodes.push_back({p.value, p.color, p.alpha});
    if (points.back().value < hi) nodes.push_back({hi, points.back().color, points.back().alpha});
    if (nodes.size() == 1) nodes.push_back(nodes.front());  // a single point at or beyond both ends
    std::vector<std::pair<Node, Node>> out;
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
        Node a = nodes[i], b = nodes[i + 1];
        if (b.value < lo || a.value > hi) continue;
        if (a.value < lo) a = lerp(a, b, lo);
        if (b.value > hi) b = lerp(a, b, hi);
        out.emplace_back(a, b);
    }
    return out;
}

// Voxel counts behind the curve, one column per pixel (the largest bin the
// column covers). Log: log(1 + count) / log(1 + largest). Linear: count /
// second-largest, so that one huge bin (the background, often most of the
// volume) does not flatten all the others; it is drawn clipped.
void drawHistogram(ImDrawList* draw, const Plot& plot, const Histogram& histogram, bool logScale) {
    const auto& counts = histogram.counts;
    const double binWidth = histogram.binWidth();
    if (counts.empty() || !(binWidth > 0.0)) return;
    std::uint64_t largest = 0, second = 0;
    for (std::uint64_t c : counts) {
        if (c > largest) second = largest, largest = c;
        else if (c > second) second = c;
    }
    if (largest == 0) return;
    const double scale = logScale ? std::log1p(double(largest)) : double(second > 0 ? second : largest);
    const ImU32 fill = styleColour(ImGuiCol_Text, 0.22f);
    const int columns = int(std::ceil(plot.width()));
    const int lastBin = int(counts.size()) - 1;
    for (int column = 0; column < columns; ++column) {
        const float x0 = plot.min.x + float(column);
        const double v0 = plot.valueAt(x0), v1 = plot.valueAt(x0 + 1.0f);
        if (v1 < histogram.lo || v0 > histogram.hi) continue;
        const int b0 = std::clamp(int(std::floor((v0 - histogram.lo) / binWidth)), 0, lastBin);
        const int b1 = std::clamp(int(std::ceil((v1 - histogram.lo) / binWidth)) - 1, b0, lastBin);
        std::uint64_t count = 0;
        for (int b = b0; b <= b1; ++b) count = std::max(count, counts[std::size_t(b)]);
        if (count == 0) continue;
        const double h = std::min(1.0, (logScale ? std::log1p(double(count)) : double(count)) / scale);
        draw->AddRectFilled(ImVec2(x0, float(plot.max.y - h * plot.height())), ImVec2(x0 + 1.0f, plot.max.y), fill);
    }
}

std::uint64_t histogramCountAt(const Histogram* histogram, double value) {
    if (!histogram || histogram->counts.empty() || !(histogram->binWidth() > 0.0)) return 0;
    if (value < histogram->lo || value > histogram->hi) return 0;
    const int bin = int(std::floor((value - histogram->lo) / histogram->binWidth()));
    return histogram->counts[std::size_t(std::clamp(bin, 0, int(histogram->counts.size()) - 1))];
}

void drawGrid(ImDrawList* draw, const Plot& plot) {
    const ImU32 line = styleColour(ImGuiCol_Text, 0.07f);
    for (int k = 1; k < 4; ++k) {
        const float x = plot.min.x + float(plot.width() * k / 4.0), y = plot.min.y + float(plot.height() * k / 4.0);
        draw->AddLine(ImVec2(x, plot.min.y), ImVec2(x, plot.max.y), line);
        draw->AddLine(ImVec2(plot.min.x, y), ImVec2(plot.max.x, y), line);
    }
}

// The area under the opacity curve filled with the function's colours
// (stronger near the curve), then the curve itself.
void drawCurve(ImDrawList* draw, const Plot& plot, const std::vector<ControlPoint>& points) {
    const auto segments = pieces(points, plot.lo, plot.hi);
    std::vector<ImVec2> line;
    for (const auto& [a, b] : segments) {
        const ImVec2 ta(plot.xOf(a.value), plot.yOf(a.alpha)), tb(plot.xOf(b.value), plot.yOf(b.alpha));
        const ImVec2 bb(tb.x, plot.max.y), ba(ta.x, plot.max.y);
        fillQuad(draw, ta, tb, bb, ba, colour(a.color, 0.75f), colour(b.color, 0.75f), colour(b.color, 0.18f),
                 colour(a.color, 0.18f));
        if (line.empty()) line.push_back(ta);
        line.push_back(tb);
    }
    if (line.size() >= 2) {
        draw->AddPolyline(line.data(), int(line.size()), IM_COL32(15, 15, 20, 160), 0, 3.5f);
        draw->AddPolyline(line.data(), int(line.size()), IM_COL32(240, 240, 240, 255), 0, 1.5f);
    }
}

// The colours alone (no opacity), as a strip under the plot, with a tick
// under every point.
void drawColourStrip(ImDrawList* draw, const Plot& plot, const std::vector<ControlPoint>& points, float top,
                     float height, int selected) {
    const ImVec2 min(plot.min.x, top), max(plot.max.x, top + height);
    draw->AddRectFilled(min, max, IM_COL32(0, 0, 0, 255));
    for (const auto& [a, b] : pieces(points, plot.lo, plot.hi)) {
        const float xa = plot.xOf(a.value), xb = plot.xOf(b.value);
        if (xb <= xa) continue;
        const ImU32 ca = colour(a.color, 1.0f), cb = colour(b.color, 1.0f);
        draw->AddRectFilledMultiColor(ImVec2(xa, min.y), ImVec2(xb, max.y), ca, cb, cb, ca);
    }
    draw->AddRect(ImVec2(min.x - 1, min.y - 1), ImVec2(max.x + 1, max.y + 1), styleColour(ImGuiCol_Border));
    for (int i = 0; i < int(points.size()); ++i) {
        const float x = plot.handle(points[i]).x;
        const ImU32 c = i == selected ? highlightColour() : IM_COL32(230, 230, 230, 255);
        draw->AddTriangleFilled(ImVec2(x, max.y - 4.0f), ImVec2(x - 4.0f, max.y + 3.0f), ImVec2(x + 4.0f, max.y + 3.0f),
                                c);
    }
}

void pointTooltip(const char* title, const ControlPoint& p) {
    ImGui::BeginTooltip();
    if (title) ImGui::TextDisabled("%s", title);
    ImGui::Text("value    %s", formatValue(p.value).c_str());
    ImGui::Text("opacity  %.3f", p.alpha);
    ImGui::ColorButton("##colour", ImVec4(p.color.r, p.color.g, p.color.b, 1.0f), ImGuiColorEditFlags_NoTooltip,
                       ImVec2(ImGui::GetTextLineHeight() * 3.0f, ImGui::GetTextLineHeight() * 0.8f));
    ImGui::EndTooltip();
}

// One frame of the editor: what its parts below share.
struct Frame1D {
    std::vector<ControlPoint>& points;  // edited here; the function is rebuilt from them
    int* selected;
    EditorState& state;
    const Plot& plot;
    const TransferFunctionEditorOptions& options;
    ImVec2 mouse;
    int hit;  // the point under the mouse, or -1
    bool hovered, active;
    double lo, hi;
};

// A new point at the mouse, coloured like the function there, held for moving.
void addPointAtMouse(Frame1D& f, const TransferFunction& tf) {
    ControlPoint p;
    p.value = snapValue(f.plot.valueAt(f.mouse.x), f.plot, f.options.valueSnap);
    p.alpha = float(std::clamp(f.plot.alphaAt(f.mouse.y), 0.0, 1.0));
    p.color = f.points.empty() ? glm::vec3(1.0f) : glm::clamp(glm::vec3(tf.evaluate(p.value)), 0.0f, 1.0f);
    const auto at = std::upper_bound(f.points.begin(), f.points.end(), p.value,
                                     [](double v, const ControlPoint& q) { return v < q.value; });
    const int index = int(at - f.points.begin());
    f.points.insert(at, p);
    *f.selected = index;
    f.state.drag = {index, ImVec2(0, 0), f.mouse};
}

// The left button: a click selects a point and starts its drag, or adds
// one; moving the mouse drags.
bool leftButton(Frame1D& f, const TransferFunction& tf) {
    Drag& drag = f.state.drag;
    bool changed = false;
    if (f.hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
        f.state.clickStamp = ++clickClock();
        if (f.hit >= 0) {
            *f.selected = f.hit;
            const ImVec2 at = f.plot.handle(f.points[std::size_t(f.hit)]);
            drag = {f.hit, ImVec2(f.mouse.x - at.x, f.mouse.y - at.y), f.mouse};
        } else if (f.points.size() < kMaxTransferFunctionPoints) {  // one more would not construct
            addPointAtMouse(f, tf);
            changed = true;
        }
    } else if (f.active && drag.point >= 0 && ImGui::IsMouseDown(ImGuiMouseButton_Left) &&
               (f.mouse.x != drag.lastMouse.x || f.mouse.y != drag.lastMouse.y)) {
        ControlPoint& p = f.points[std::size_t(drag.point)];
        const ImVec2 target(f.mouse.x - drag.grabOffset.x, f.mouse.y - drag.grabOffset.y);
        const double value = snapValue(f.plot.valueAt(target.x), f.plot, f.options.valueSnap);
        const float alpha = float(std::clamp(f.plot.alphaAt(target.y), 0.0, 1.0));
        if (value != p.value || alpha != p.alpha) {
            p.value = value, p.alpha = alpha;
            drag.point = *f.selected = resort(f.points, drag.point);
            changed = true;
        }
        drag.lastMouse = f.mouse;
    }
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) drag.point = -1;
    return changed;
}

// Removal: a right click on a handle, or Delete for the selected point
// (never below two points).
bool removal(Frame1D& f) {
    int remove = -1;
    if (f.hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && f.hit >= 0 && f.state.drag.point < 0) {
        remove = f.hit;
        f.state.clickStamp = ++clickClock();
    }
    if (remove < 0 && *f.selected >= 0 && f.state.drag.point < 0 && f.state.clickStamp == clickClock() &&
        deletePressed())
        remove = *f.selected;
    if (remove < 0 || f.points.size() <= 2) return false;
    f.points.erase(f.points.begin() + remove);
    if (*f.selected == remove) *f.selected = -1;
    else if (*f.selected > remove) --*f.selected;
    return true;
}

// The frame, grid, histogram, coloured area and curve, the opacity axis's
// top and the handles (the selected on top).
void drawPlot(const Frame1D& f, const EditorFrame& frame) {
    const Plot& plot = f.plot;
    const float rounding = ImGui::GetStyle().FrameRounding;
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(frame.origin, frame.max, styleColour(ImGuiCol_FrameBg), rounding);
    draw->PushClipRect(plot.min, plot.max, true);
    drawGrid(draw, plot);
    if (f.options.histogram) drawHistogram(draw, plot, *f.options.histogram, f.options.logHistogram);
    drawCurve(draw, plot, f.points);
    if (f.hovered && f.state.drag.point < 0 && f.hit < 0)
        draw->AddLine(ImVec2(f.mouse.x, plot.min.y), ImVec2(f.mouse.x, plot.max.y), styleColour(ImGuiCol_Text, 0.3f));
    draw->PopClipRect();
    // The opacity at the top: "1", or the zoomed axis's top, highlighted.
    const std::string top = "opacity " + formatValue(plot.top);
    drawLabel(draw, ImVec2(plot.min.x + 3.0f, plot.min.y + 1.0f), top.c_str(),
              f.state.zoom > 1.0f ? highlightColour() : styleColour(ImGuiCol_TextDisabled));
    draw->PushClipRect(frame.origin, frame.max, true);
    for (int i = 0; i < int(f.points.size()); ++i)
        if (i != *f.selected)
            drawHandle(draw, plot.handle(f.points[i]), colour(f.points[i].color, 1.0f), false, i == f.hit);
    if (*f.selected >= 0) {
        const ControlPoint& p = f.points[std::size_t(*f.selected)];
        drawHandle(draw, plot.handle(p), colour(p.color, 1.0f), true, *f.selected == f.hit);
    }
    draw->PopClipRect();
    draw->AddRect(frame.origin, frame.max, styleColour(ImGuiCol_Border), rounding);
}

// The dragged or hovered point, else the position under the mouse.
void hoverTooltip(const Frame1D& f) {
    if (f.state.drag.point >= 0 && f.active) {
        pointTooltip(nullptr, f.points[std::size_t(f.state.drag.point)]);
    } else if (f.hovered && f.hit >= 0) {
        char title[48];
        std::snprintf(title, sizeof title, "point %d of %d", f.hit + 1, int(f.points.size()));
        pointTooltip(title, f.points[std::size_t(f.hit)]);
    } else if (f.hovered) {
        const double value = std::clamp(f.plot.valueAt(f.mouse.x), f.lo, f.hi);
        const double alpha = std::clamp(f.plot.alphaAt(f.mouse.y), 0.0, f.plot.top);
        ImGui::BeginTooltip();
        ImGui::Text("value    %s", formatValue(value).c_str());
        ImGui::Text("opacity  %.3f", alpha);
        if (!f.points.empty()) {
            const TransferFunction current(f.points);
            ImGui::TextDisabled("function opacity %.3f", current.evaluate(value).a);
        }
        if (f.options.histogram)
            ImGui::TextDisabled("voxels   %llu", (unsigned long long)histogramCountAt(f.options.histogram, value));
        ImGui::EndTooltip();
    }
}

// The colour strip and the range's ends, with the label between them.
void colourStripAndAxis(const Frame1D& f, const EditorFrame& frame, const char* label) {
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const float stripHeight = 10.0f;
    drawColourStrip(draw, f.plot, f.points, ImGui::GetCursorScreenPos().y, stripHeight, *f.selected);
    ImGui::Dummy(ImVec2(frame.width, stripHeight + 3.0f));
    const float y = ImGui::GetCursorScreenPos().y;
    const std::string loText = formatValue(f.lo), hiText = formatValue(f.hi), title = visibleLabel(label);
    const ImU32 text = styleColour(ImGuiCol_TextDisabled);
    draw->AddText(ImVec2(f.plot.min.x, y), text, loText.c_str());
    draw->AddText(ImVec2(f.plot.max.x - ImGui::CalcTextSize(hiText.c_str()).x, y), text, hiText.c_str());
    if (!title.empty())
        draw->AddText(ImVec2(frame.origin.x + (frame.width - ImGui::CalcTextSize(title.c_str()).x) * 0.5f, y),
                      styleColour(ImGuiCol_Text), title.c_str());
    ImGui::Dummy(ImVec2(frame.width, ImGui::GetTextLineHeight()));
}

// The selected point's colour, value, opacity and delete button.
bool selectedPointControls(Frame1D& f) {
    const ImGuiStyle& style = ImGui::GetStyle();
    ImGui::PushID("##point");
    bool changed = false;
    ControlPoint& p = f.points[std::size_t(*f.selected)];
    float rgb[3] = {p.color.r, p.color.g, p.color.b};
    if (ImGui::ColorEdit3("##colour", rgb, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_NoLabel))
        p.color = glm::clamp(glm::vec3(rgb[0], rgb[1], rgb[2]), 0.0f, 1.0f), changed = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("colour of point %d (click for a picker)", *f.selected + 1);
    ImGui::SameLine();
    const float deleteWidth = ImGui::CalcTextSize("delete").x + 2.0f * style.FramePadding.x;
    const float fields = ImGui::GetContentRegionAvail().x - deleteWidth - 2.0f * style.ItemSpacing.x;
    ImGui::SetNextItemWidth(fields * 0.5f);
    double value = p.value;
    const double speed = (f.hi - f.lo) / 1000.0;
    if (ImGui::DragScalar("##value", ImGuiDataType_Double, &value, float(speed), &f.lo, &f.hi, "value %.6g",
                          ImGuiSliderFlags_AlwaysClamp) &&
        value != p.value) {
        p.value = snapValue(value, f.plot, f.options.valueSnap);
        *f.selected = resort(f.points, *f.selected);
        changed = true;
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(fields * 0.5f);
    ControlPoint& q = f.points[std::size_t(*f.selected)];  // (resort may have moved it)
    float alpha = q.alpha;
    if (ImGui::SliderFloat("##opacity", &alpha, 0.0f, 1.0f, "opacity %.3f", ImGuiSliderFlags_AlwaysClamp) &&
        alpha != q.alpha)
        q.alpha = std::clamp(alpha, 0.0f, 1.0f), changed = true;
    ImGui::SameLine();
    ImGui::BeginDisabled(f.points.size() <= 2);
    if (ImGui::Button("delete")) {
        f.points.erase(f.points.begin() + *f.selected);
        *f.selected = -1;
        changed = true;
    }
    ImGui::EndDisabled();
    ImGui::PopID();
    return changed;
}

}  // namespace

bool TransferFunctionEditor(const char* label, TransferFunction* tf, const TransferFunctionEditorOptions& options,
                            int* selected) {
    ImGui::PushID(label);
    const ImGuiID id = ImGui::GetID("##editor");
    if (!selected) selected = ImGui::GetStateStorage()->GetIntRef(ImGui::GetID("##selected"), -1);
    std::vector<ControlPoint> points = tf->points();
    if (*selected >= int(points.size()) || *selected < -1) *selected = -1;

    double lo = options.range.x, hi = options.range.y;
    if (!(std::isfinite(lo) && std::isfinite(hi))) lo = 0.0, hi = 1.0;
    if (!(hi > lo)) hi = lo + 1.0;
    EditorState& state = persistentState<EditorState>(id);
    const EditorFrame frame = editorFrame(options.height, &state.zoom, kMaxZoom);
    const Plot plot{frame.plotMin(), frame.plotMax(), lo, hi, 1.0 / double(state.zoom)};
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    if (state.drag.point >= int(points.size())) state.drag.point = -1;
    const int hit = frame.hovered ? handleAt(points, plot, mouse) : -1;
    Frame1D f{points, selected, state, plot, options, mouse, hit, frame.hovered, frame.active, lo, hi};

    bool changed = leftButton(f, *tf);
    changed |= removal(f);
    drawPlot(f, frame);
    hoverTooltip(f);
    colourStripAndAxis(f, frame, label);
    if (options.showPointControls) {
        if (*selected >= 0)
            changed |= selectedPointControls(f);
        else
            ImGui::TextDisabled("click: add   drag: move   right-click: delete   wheel: zoom opacity");
    }

    if (changed) *tf = TransferFunction(std::move(points));
    ImGui::PopID();
    return changed;
}

}  // namespace voxlab
