// voxlab: the slice viewer panel and the slice planes over the 3D view (see slice_viewer.h).
#include "voxlab_gl.h"

#include "voxlab/slice_viewer.h"
#include "grey_texture.h"

#include <imgui_internal.h>  // to see whether the caller chose the window's size

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace voxlab {
namespace {

ImU32 axisColour(int axis, float alpha = 1.0f) {
    const glm::vec3 c = sliceAxisColour(axis);
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, alpha));
}

ImVec2 operator+(ImVec2 a, ImVec2 b) { return {a.x + b.x, a.y + b.y}; }
ImVec2 operator-(ImVec2 a, ImVec2 b) { return {a.x - b.x, a.y - b.y}; }

// The letter of the volume axis a slice index counts along.
const char* axisLetter(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

// Text with a dark plate behind it, so it reads over any slice.
void labelAt(ImDrawList* list, ImVec2 pos, ImU32 colour, const char* text) {
    const ImVec2 size = ImGui::CalcTextSize(text);
    list->AddRectFilled(pos - ImVec2(3, 1), pos + size + ImVec2(3, 1), IM_COL32(0, 0, 0, 150), 3.0f);
    list->AddText(pos, colour, text);
}

// The screen rectangle a view is centred in.
struct Cell {
    ImVec2 min, max;
};

// The three views laid out in the space [origin, origin + avail] at one
// common scale (screen pixels per world unit), so lengths compare across
// views. Three arrangements are tried and the one with the largest scale wins:
//   grid:    axial above coronal (they share x), sagittal beside coronal (they
//            share z), so the crosshair lines run straight from view to view;
//            the fourth cell (top right) is returned as `spare`;
//   row:     axial | coronal | sagittal;
//   column:  axial over coronal over sagittal.
float layoutViews(glm::dvec3 worldSize, ImVec2 origin, ImVec2 avail, float gap, Cell cells[3], Cell* spare) {
    const double X = worldSize.x, Y = worldSize.y, Z = worldSize.z;
    const double gridScale = std::min((avail.x - gap) / (X + Y), (avail.y - gap) / (Y + Z));
    const double rowScale = std::min((avail.x - 2 * gap) / (X + X + Y), avail.y / std::max(Y, Z));
    const double columnScale = std::min(avail.x / std::max(X, Y), (avail.y - 2 * gap) / (Y + Z + Z));
    const double scale = std::max({gridScale, rowScale, columnScale, 1e-6});
    const auto cellAt = [&](double x, double y, double w, double h) {
        return Cell{origin + ImVec2(float(x), float(y)), origin + ImVec2(float(x + w), float(y + h))};
    };
    *spare = Cell{origin, origin};
    if (scale == gridScale) {
        // The grid centred across the space, at its top.
        const double w = scale * (X + Y) + gap;
        const double x0 = 0.5 * (avail.x - w), y0 = 0.0;
        cells[kAxialAxis] = cellAt(x0, y0, scale * X, scale * Y);
        cells[kCoronalAxis] = cellAt(x0, y0 + scale * Y + gap, scale * X, scale * Z);
        cells[kSagittalAxis] = cellAt(x0 + scale * X + gap, y0 + scale * Y + gap, scale * Y, scale * Z);
        *spare = cellAt(x0 + scale * X + gap, y0, scale * Y, scale * Y);
    } else if (scale == rowScale) {
        const double w = scale * (X + X + Y) + 2 * gap;
        const double x0 = 0.5 * (avail.x - w);
        const double h = scale * std::max(Y, Z);
        cells[kAxialAxis] = cellAt(x0, 0, scale * X, h);
        cells[kCoronalAxis] = cellAt(x0 + scale * X + gap, 0, scale * X, h);
        cells[kSagittalAxis] = cellAt(x0 + 2 * (scale * X + gap), 0, scale * Y, h);
    } else {
        const double y0 = 0.0;
        cells[kAxialAxis] = cellAt(0, y0, avail.x, scale * Y);
        cells[kCoronalAxis] = cellAt(0, y0 + scale * Y + gap, avail.x, scale * Z);
        cells[kSagittalAxis] = cellAt(0, y0 + scale * (Y + Z) + 2 * gap, avail.x, scale * Z);
    }
    return float(scale);
}

// The slice pixel under a screen position inside an image rectangle.
glm::ivec2 pixelUnder(ImVec2 mouse, ImVec2 imageMin, ImVec2 imageMax, glm::ivec2 imageSize) {
    const double u = (mouse.x - imageMin.x) / std::max(imageMax.x - imageMin.x, 1e-6f) * imageSize.x;
    const double v = (mouse.y - imageMin.y) / std::max(imageMax.y - imageMin.y, 1e-6f) * imageSize.y;
    return {int(std::floor(u)), int(std::floor(v))};
}

// The widths of a few kinds of widget, to decide whether the next one still fits on the line.
float labelWidth(const char* label) { return ImGui::GetStyle().ItemInnerSpacing.x + ImGui::CalcTextSize(label).x; }
float buttonWidth(const char* label) { return ImGui::CalcTextSize(label).x + 2 * ImGui::GetStyle().FramePadding.x; }
float checkboxWidth(const char* label) { return ImGui::GetFrameHeight() + labelWidth(label); }

// SameLine() when an item `width` wide still fits in the window after the
// last one; otherwise the item starts a new line. Returns whether it fits.
bool sameLineIfFits(float width) {
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    const bool fits = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width <= right;
    if (fits) ImGui::SameLine();
    return fits;
}

// Two short arrows in the image's bottom-left corner showing which way the
// image's column and row axes grow, each in its axis colour (x red, y green, z blue).
void drawAxisGizmo(ImDrawList* list, ImVec2 imageMin, ImVec2 imageMax, glm::ivec2 imageAxes, bool rowsGrowDown) {
    const float length = 22.0f, head = 4.0f, margin = 9.0f;
    if (imageMax.x - imageMin.x < 3 * length || imageMax.y - imageMin.y < 3 * length) return;
    const ImVec2 origin(imageMin.x + margin, rowsGrowDown ? imageMax.y - margin - length : imageMax.y - margin);
    const auto arrow = [&](ImVec2 direction, int axis) {
        const ImU32 colour = axisColour(axis, 0.9f);
        const ImVec2 tip(origin.x + direction.x * length, origin.y + direction.y * length);
        const ImVec2 side(-direction.y * head, direction.x * head);
        const ImVec2 back(tip.x - direction.x * head * 1.6f, tip.y - direction.y * head * 1.6f);
        list->AddLine(origin, back, colour, 2.0f);
        list->AddTriangleFilled(tip, back + side, back - side, colour);
        const char* letter = axisLetter(axis);
        const ImVec2 size = ImGui::CalcTextSize(letter);
        // The letter beside the tip: past it for the horizontal arrow, to its right for the vertical one.
        const ImVec2 at = direction.x != 0.0f ? ImVec2(tip.x + 3, tip.y - 0.5f * size.y)
                                              : ImVec2(tip.x + 5, tip.y - 0.5f * size.y);
        list->AddText(at, colour, letter);
    };
    arrow(ImVec2(1, 0), imageAxes.x);
    arrow(ImVec2(0, rowsGrowDown ? 1.0f : -1.0f), imageAxes.y);
}

}  // namespace

SliceViewer::~SliceViewer() = default;

void SliceViewer::invalidate() {
    for (View& view : views_) view.index = -1;
}

void SliceViewer::upload(View& view, const Volume& volume, int axis, int index, glm::dvec2 window) {
    if (view.texture && view.data == volume.data() && view.dims == volume.dims() && view.index == index &&
        view.window == window && view.smooth == smooth)
        return;
    const SliceImage image = extractSlice(volume, axis, index, window);

    // Leave the GL state as we found it: the viewer's renderers share it.
    GLint previousTexture = 0, previousAlignment = 4, previousRowLength = 0, previousUnpackBuffer = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &previousTexture);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &previousAlignment);
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &previousRowLength);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &previousUnpackBuffer);

    view.texture.ensure();
    glBindTexture(GL_TEXTURE_2D, view.texture);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of odd widths are not padded
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    viewer::uploadGreyTexture(image.width, image.height, image.grey.data(), viewer::GreyAs::Opaque);
    const GLint filter = smooth ? GL_LINEAR : GL_NEAREST;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

    glBindTexture(GL_TEXTURE_2D, GLuint(previousTexture));
    glPixelStorei(GL_UNPACK_ALIGNMENT, previousAlignment);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, previousRowLength);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(previousUnpackBuffer));

    view.data = volume.data();
    view.dims = volume.dims();
    view.index = index;
    view.window = window;
    view.smooth = smooth;
    ++uploads_;
}

bool SliceViewer::draw(const char* title, const Volume& volume, SliceCursor* cursor, bool* open) {
    // A default size for a first appearance, unless the caller chose one.
    if (!(ImGui::GetCurrentContext()->NextWindowData.Flags & ImGuiNextWindowDataFlags_HasSize))
        ImGui::SetNextWindowSize(ImVec2(560, 620), ImGuiCond_FirstUseEver);
    // The views take the scroll wheel themselves (it moves the slices).
    const bool visible =
        ImGui::Begin(title, open, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
    bool changed = false;
    hovered_.reset();
    if (visible) changed = drawContents(volume, cursor);
    ImGui::End();
    return changed;
}

int SliceViewer::displayRow(const glm::ivec3& dims, int axis, int row) const {
    return !zUp && axis != kAxialAxis ? sliceImageSize(dims, axis).y - 1 - row : row;
}

// Window/level fields: level and width in data units, and a reset; the
// smooth and z-up switches.
void SliceViewer::windowControls(SliceCursor* cursor, const glm::dvec2& range, double span) {
    float level = float(windowLevel(cursor->window)), width = float(windowWidth(cursor->window));
    const float speed = float(span / 500.0);
    const float fieldWidth = std::max(70.0f, ImGui::GetFontSize() * 7.0f);
    ImGui::SetNextItemWidth(fieldWidth);
    const bool levelEdited = ImGui::DragFloat("level", &level, speed, 0.0f, 0.0f, "%.5g");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("window centre (data units); right-drag in a view: up/down");
    sameLineIfFits(fieldWidth + labelWidth("width"));
    ImGui::SetNextItemWidth(fieldWidth);
    const bool widthEdited =
        ImGui::DragFloat("width", &width, speed, float(span * 1e-3), FLT_MAX, "%.5g", ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("window width (data units); right-drag in a view: left/right");
    if (levelEdited || widthEdited) cursor->window = windowFromLevelWidth(level, width);
    sameLineIfFits(buttonWidth("reset"));
    if (ImGui::Button("reset")) cursor->window = range.y > range.x ? range : glm::dvec2(range.x, range.x + 1.0);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("window = the volume's value range %g .. %g", range.x, range.y);
    sameLineIfFits(checkboxWidth("smooth"));
    ImGui::Checkbox("smooth", &smooth);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("bilinear filtering (off: each voxel a sharp square)");
    sameLineIfFits(checkboxWidth("z up"));
    ImGui::Checkbox("z up", &zUp);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("coronal and sagittal views with z growing upwards (off: downwards, for volumes\n"
                          "stored from the top of the head down, such as cthead and headsq)");
}

// The view's image, centred in its cell at `scale` screen pixels per world unit.
void SliceViewer::placeView(int axis, const Volume& volume, float scale, ImVec2 cellMin, ImVec2 cellMax) {
    View& view = views_[axis];
    const glm::dvec2 world = sliceWorldSize(volume.dims(), volume.spacing(), axis);
    const ImVec2 size(std::max(1.0f, std::round(float(world.x) * scale)), std::max(1.0f, std::round(float(world.y) * scale)));
    const ImVec2 cellSize = cellMax - cellMin;
    view.imageMin = ImVec2(std::floor(cellMin.x + 0.5f * (cellSize.x - size.x)), std::floor(cellMin.y + 0.5f * (cellSize.y - size.y)));
    view.imageMax = view.imageMin + size;
}

// A view's mouse and keys: a click moves the crosshair, a double click
// enlarges, a right drag sets the window, the wheel and arrows step the slice.
void SliceViewer::viewInput(int axis, const glm::ivec3& dims, SliceCursor* cursor, const glm::dvec2& range) {
    View& view = views_[axis];
    ImGuiIO& io = ImGui::GetIO();
    ImGui::SetCursorScreenPos(view.imageMin);
    ImGui::PushID(axis);
    ImGui::InvisibleButton("view", view.imageMax - view.imageMin,
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    ImGui::PopID();
    if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) enlarged = enlarged < 0 ? axis : -1;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("double click: %s", enlarged < 0 ? "enlarge" : "all three views");
    const glm::ivec2 imageSize = sliceImageSize(dims, axis);
    glm::ivec2 pixel = pixelUnder(io.MousePos, view.imageMin, view.imageMax, imageSize);
    pixel.y = displayRow(dims, axis, pixel.y);
    if (ImGui::IsItemActive() && ImGui::IsMouseDown(ImGuiMouseButton_Left))
        cursor->voxel = sliceVoxel(dims, axis, cursor->voxel[axis], pixel);
    if (ImGui::IsItemActive() && ImGui::IsMouseDown(ImGuiMouseButton_Right) &&
        (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f))
        cursor->window = dragWindow(cursor->window, io.MouseDelta.x, io.MouseDelta.y, range);
    if (!ImGui::IsItemHovered() && !ImGui::IsItemActive()) return;

    hovered_ = sliceVoxel(dims, axis, cursor->voxel[axis], pixel);
    int step = 0;
    wheel_ += io.MouseWheel;
    const int wheelSteps = int(wheel_);  // whole notches; a touchpad's fractions add up
    wheel_ -= float(wheelSteps);
    step += wheelSteps;
    const auto pressed = [](ImGuiKey key) { return ImGui::IsKeyPressed(ImGui::GetKeyIndex(key), true); };
    if (pressed(ImGuiKey_UpArrow) || pressed(ImGuiKey_RightArrow)) step += 1;
    if (pressed(ImGuiKey_DownArrow) || pressed(ImGuiKey_LeftArrow)) step -= 1;
    if (pressed(ImGuiKey_PageUp)) step += 10;
    if (pressed(ImGuiKey_PageDown)) step -= 10;
    if (step != 0) {
        cursor->voxel[axis] = std::clamp(cursor->voxel[axis] + step, 0, dims[axis] - 1);
        (*hovered_)[axis] = cursor->voxel[axis];
    }
}

// A view: its slice image, the crosshair, the voxel under the mouse, its
// frame, name and axes.
void SliceViewer::drawView(ImDrawList* list, int axis, const Volume& volume, const SliceCursor& cursor) {
    View& view = views_[axis];
    const glm::ivec3 dims = volume.dims();
    upload(view, volume, axis, cursor.voxel[axis], cursor.window);
    const ImVec2 a = view.imageMin, b = view.imageMax;
    const glm::ivec2 imageSize = sliceImageSize(dims, axis);
    const ImVec2 texel((b.x - a.x) / imageSize.x, (b.y - a.y) / imageSize.y);
    const bool hot = hovered_ && ImGui::IsMouseHoveringRect(a, b);

    const bool flipped = displayRow(dims, axis, 0) != 0;
    list->AddImage(ImTextureID(std::intptr_t(view.texture.name())), a, b, ImVec2(0, flipped ? 1 : 0),
                   ImVec2(1, flipped ? 0 : 1));

    // Crosshair: the other two slices as lines in their colours, with a
    // gap around the crosshair voxel so that it stays visible.
    glm::ivec2 centrePixel = slicePixel(dims, axis, cursor.voxel);
    centrePixel.y = displayRow(dims, axis, centrePixel.y);
    const ImVec2 centre(a.x + (centrePixel.x + 0.5f) * texel.x, a.y + (centrePixel.y + 0.5f) * texel.y);
    const float gapX = std::max(6.0f, texel.x), gapY = std::max(6.0f, texel.y);
    const glm::ivec2 imageAxes = sliceImageAxes(axis);
    const ImU32 vertical = axisColour(imageAxes.x, 0.8f), horizontal = axisColour(imageAxes.y, 0.8f);
    list->AddLine(ImVec2(centre.x, a.y), ImVec2(centre.x, centre.y - gapY), vertical, 1.0f);
    list->AddLine(ImVec2(centre.x, centre.y + gapY), ImVec2(centre.x, b.y), vertical, 1.0f);
    list->AddLine(ImVec2(a.x, centre.y), ImVec2(centre.x - gapX, centre.y), horizontal, 1.0f);
    list->AddLine(ImVec2(centre.x + gapX, centre.y), ImVec2(b.x, centre.y), horizontal, 1.0f);

    // The voxel under the mouse, outlined once voxels are big enough to see.
    if (hot && texel.x >= 4.0f && texel.y >= 4.0f) {
        glm::ivec2 p = slicePixel(dims, axis, *hovered_);
        p.y = displayRow(dims, axis, p.y);
        const ImVec2 q(a.x + p.x * texel.x, a.y + p.y * texel.y);
        list->AddRect(q, q + texel, IM_COL32(255, 255, 255, 140));
    }

    // Frame and labels: the slice's name and index, and which way the axes grow.
    list->AddRect(a - ImVec2(1, 1), b + ImVec2(1, 1), axisColour(axis, hot ? 1.0f : 0.75f), 0.0f, 0, hot ? 2.0f : 1.0f);
    char text[64];
    std::snprintf(text, sizeof text, "%s  %s %d/%d", sliceAxisName(axis), axisLetter(axis), cursor.voxel[axis],
                  dims[axis] - 1);
    list->PushClipRect(a, b, true);
    labelAt(list, a + ImVec2(5, 3), axisColour(axis), text);
    const bool rowsGrowDown = axis == kAxialAxis || flipped;  // does the image's row axis point down?
    drawAxisGizmo(list, a, b, imageAxes, rowsGrowDown);
    list->PopClipRect();
}

namespace {

// The spare grid cell: the volume's description and the controls.
void describeVolume(const Volume& volume, ImVec2 min, ImVec2 max) {
    if (max.x - min.x <= 120.0f || max.y - min.y <= 5 * ImGui::GetTextLineHeightWithSpacing()) return;
    const glm::ivec3 dims = volume.dims();
    const glm::dvec3 spacing = volume.spacing();
    ImGui::SetCursorScreenPos(min + ImVec2(8, 4));
    ImGui::PushTextWrapPos(max.x - 4);
    ImGui::BeginGroup();
    ImGui::Text("%s", volume.name().c_str());
    ImGui::TextDisabled("%d x %d x %d %s", dims.x, dims.y, dims.z, voxelTypeName(volume.type()));
    ImGui::TextDisabled("spacing %g x %g x %g", spacing.x, spacing.y, spacing.z);
    ImGui::Spacing();
    ImGui::TextDisabled("click: move crosshair");
    ImGui::TextDisabled("scroll, arrows: slice");
    ImGui::TextDisabled("right-drag: window/level");
    ImGui::TextDisabled("double click: enlarge");
    ImGui::EndGroup();
    ImGui::PopTextWrapPos();
}

}  // namespace

// Readout: the voxel under the mouse, or else the crosshair's, in data units.
void SliceViewer::readout(const Volume& volume, const SliceCursor& cursor, ImVec2 at) {
    ImGui::SetCursorScreenPos(at);
    const glm::ivec3 read = hovered_ ? *hovered_ : cursor.voxel;
    ImGui::TextColored(hovered_ ? ImVec4(1, 1, 1, 1) : ImVec4(0.7f, 0.7f, 0.7f, 1), "%s (%d, %d, %d)  value %.6g",
                       hovered_ ? "mouse" : "crosshair", read.x, read.y, read.z, volume.value(read.x, read.y, read.z));
    char windowText[64];
    std::snprintf(windowText, sizeof windowText, "  window %.5g .. %.5g", cursor.window.x, cursor.window.y);
    if (sameLineIfFits(ImGui::CalcTextSize(windowText).x)) ImGui::TextDisabled("%s", windowText);
}

bool SliceViewer::drawContents(const Volume& volume, SliceCursor* cursor) {
    hovered_.reset();
    const glm::ivec3 dims = volume.dims();
    if (volume.voxelCount() == 0) {
        ImGui::TextDisabled("no volume");
        return false;
    }
    const SliceCursor before = *cursor;
    cursor->voxel = clampVoxel(cursor->voxel, dims);
    const glm::dvec2 range = volume.valueRange();
    const double span = std::max(range.y - range.x, 1e-12);
    // An empty window (a caller's default) becomes the range's width about its level.
    if (!(cursor->window.y > cursor->window.x))
        cursor->window = windowFromLevelWidth(windowLevel(cursor->window), span);

    ImGui::PushID(this);
    windowControls(cursor, range, span);

    // The views share what is left, less one line for the readout.
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImVec2 avail = ImGui::GetContentRegionAvail();
    avail.y -= ImGui::GetTextLineHeightWithSpacing();
    avail = ImVec2(std::max(avail.x, 30.0f), std::max(avail.y, 30.0f));
    Cell cells[3], spare;
    if (enlarged < 0 || enlarged > 2) enlarged = -1;
    float scale = layoutViews(volume.extent(), origin, avail, 6.0f, cells, &spare);
    if (enlarged >= 0) {  // one view fills the space
        const glm::dvec2 world = sliceWorldSize(dims, volume.spacing(), enlarged);
        scale = float(std::max(1e-6, std::min(avail.x / world.x, avail.y / world.y)));
        cells[enlarged] = Cell{origin, origin + avail};
        spare = Cell{origin, origin};
    }

    // Input first, for all three views, then drawing: a click shows in every view in the same frame.
    for (int axis = 0; axis < 3; ++axis) {
        if (!shown(axis)) {
            views_[axis].imageMin = views_[axis].imageMax = origin;
            continue;
        }
        placeView(axis, volume, scale, cells[axis].min, cells[axis].max);
        viewInput(axis, dims, cursor, range);
    }
    ImDrawList* list = ImGui::GetWindowDrawList();
    for (int axis = 0; axis < 3; ++axis)
        if (shown(axis)) drawView(list, axis, volume, *cursor);
    describeVolume(volume, spare.min, spare.max);
    readout(volume, *cursor, ImVec2(origin.x, origin.y + avail.y + ImGui::GetStyle().ItemSpacing.y));
    ImGui::PopID();

    return cursor->voxel != before.voxel || cursor->window != before.window;
}

void drawSlicePlanes(ImDrawList* list, const Camera& camera, glm::dvec3 extent, glm::dvec3 spacing,
                     glm::ivec3 voxel, ImVec2 viewportMin, ImVec2 viewportMax) {
    // Camera pixels -> screen: the rendered image is stretched over the viewport.
    const double sx = (viewportMax.x - viewportMin.x) / double(camera.width);
    const double sy = (viewportMax.y - viewportMin.y) / double(camera.height);
    const auto toScreen = [&](glm::dvec2 p) {
        return ImVec2(float(viewportMin.x + p.x * sx), float(viewportMin.y + p.y * sy));
    };
    list->PushClipRect(viewportMin, viewportMax, true);
    std::vector<ImVec2> outlines[3];
    for (int axis = 0; axis < 3; ++axis) {
        for (const glm::dvec2& p : slicePlaneOutline(camera, extent, spacing, axis, voxel[axis]))
            outlines[axis].push_back(toScreen(p));
        if (outlines[axis].size() >= 3)
            list->AddConvexPolyFilled(outlines[axis].data(), int(outlines[axis].size()), axisColour(axis, 0.08f));
    }
    for (int axis = 0; axis < 3; ++axis)
        if (outlines[axis].size() >= 2)
            list->AddPolyline(outlines[axis].data(), int(outlines[axis].size()), axisColour(axis, 0.95f),
                              ImDrawFlags_Closed, 1.5f);
    // The crosshair voxel's centre, where the three planes meet.
    const std::vector<glm::dvec2> centre = projectPolygon(camera, {(glm::dvec3(voxel) + 0.5) * spacing});
    if (!centre.empty()) {
        list->AddCircleFilled(toScreen(centre[0]), 4.0f, IM_COL32(0, 0, 0, 160));
        list->AddCircleFilled(toScreen(centre[0]), 2.5f, IM_COL32(255, 255, 255, 230));
    }
    list->PopClipRect();
}

}  // namespace voxlab
