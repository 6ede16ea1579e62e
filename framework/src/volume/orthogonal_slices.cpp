// voxlab: orthogonal slices (see orthogonal_slices.h for the orientations).
#include "voxlab/orthogonal_slices.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "voxlab/error.h"

namespace voxlab {
namespace {

void checkAxis(int axis) {
    if (axis < 0 || axis > 2) throw Error("slice axis must be 0 (sagittal), 1 (coronal) or 2 (axial), got " +
                                          std::to_string(axis));
}

// Coronal and sagittal images put z upwards, so their rows run against k.
bool rowsRunAgainstAxis(int axis) { return axis != kAxialAxis; }

}  // namespace

const char* sliceAxisName(int axis) {
    checkAxis(axis);
    static const char* const names[] = {"sagittal", "coronal", "axial"};
    return names[axis];
}

glm::vec3 sliceAxisColour(int axis) {
    checkAxis(axis);
    // Saturated but light enough to read as text on a dark background.
    static const glm::vec3 colours[] = {{0.94f, 0.33f, 0.31f}, {0.36f, 0.82f, 0.38f}, {0.33f, 0.58f, 1.0f}};
    return colours[axis];
}

SliceCursor initialSliceCursor(const Volume& volume) {
    SliceCursor c;
    c.voxel = volume.dims() / 2;
    c.window = volume.valueRange();
    if (c.window.y <= c.window.x) c.window.y = c.window.x + 1.0;  // a constant volume still gets a valid window
    return c;
}

glm::ivec3 clampVoxel(glm::ivec3 voxel, glm::ivec3 dims) {
    return glm::clamp(voxel, glm::ivec3(0), glm::max(dims - 1, glm::ivec3(0)));
}

glm::ivec2 sliceImageAxes(int axis) {
    checkAxis(axis);
    static const glm::ivec2 axes[] = {{1, 2}, {0, 2}, {0, 1}};
    return axes[axis];
}

glm::ivec2 sliceImageSize(glm::ivec3 dims, int axis) {
    const glm::ivec2 a = sliceImageAxes(axis);
    return {dims[a.x], dims[a.y]};
}

glm::dvec2 sliceWorldSize(glm::ivec3 dims, glm::dvec3 spacing, int axis) {
    const glm::ivec2 a = sliceImageAxes(axis);
    return {dims[a.x] * spacing[a.x], dims[a.y] * spacing[a.y]};
}

glm::ivec3 sliceVoxel(glm::ivec3 dims, int axis, int index, glm::ivec2 pixel) {
    const glm::ivec2 a = sliceImageAxes(axis);
    glm::ivec3 voxel(0);
    voxel[axis] = index;
    voxel[a.x] = pixel.x;
    voxel[a.y] = rowsRunAgainstAxis(axis) ? dims[a.y] - 1 - pixel.y : pixel.y;
    return clampVoxel(voxel, dims);
}

glm::ivec2 slicePixel(glm::ivec3 dims, int axis, glm::ivec3 voxel) {
    const glm::ivec2 a = sliceImageAxes(axis);
    voxel = clampVoxel(voxel, dims);
    return {voxel[a.x], rowsRunAgainstAxis(axis) ? dims[a.y] - 1 - voxel[a.y] : voxel[a.y]};
}

std::uint8_t windowedGrey(double value, glm::dvec2 window) {
    if (!(window.y > window.x)) return value >= window.x ? 255 : 0;
    const double t = std::clamp((value - window.x) / (window.y - window.x), 0.0, 1.0);
    return std::uint8_t(std::lround(t * 255.0));
}

SliceImage extractSlice(const Volume& volume, int axis, int index, glm::dvec2 window) {
    const glm::ivec3 dims = volume.dims();
    const glm::ivec2 size = sliceImageSize(dims, axis);
    const glm::ivec2 a = sliceImageAxes(axis);
    SliceImage image;
    image.width = size.x;
    image.height = size.y;
    image.pixelAspect = volume.spacing()[a.y] / volume.spacing()[a.x];
    image.grey.resize(std::size_t(size.x) * size.y);
    if (volume.voxelCount() == 0) return image;
    index = std::clamp(index, 0, dims[axis] - 1);
    for (int v = 0; v < size.y; ++v) {
        std::uint8_t* row = &image.grey[std::size_t(v) * size.x];
        for (int u = 0; u < size.x; ++u) {
            const glm::ivec3 p = sliceVoxel(dims, axis, index, {u, v});
            row[u] = windowedGrey(volume.value(p.x, p.y, p.z), window);
        }
    }
    return image;
}

glm::dvec2 windowFromLevelWidth(double level, double width) {
    return {level - 0.5 * width, level + 0.5 * width};
}

glm::dvec2 dragWindow(glm::dvec2 window, double dx, double dy, glm::dvec2 valueRange) {
    const double range = std::max(valueRange.y - valueRange.x, 1e-12);
    const double perPixel = range / 500.0;
    const double minWidth = std::max(range * 1e-3, 1e-12);
    const double width = std::max(windowWidth(window) + dx * perPixel, minWidth);
    // Screen y grows downwards: dragging down (dy > 0) raises the level.
    const double level = windowLevel(window) + dy * perPixel;
    return windowFromLevelWidth(level, width);
}

std::array<glm::dvec3, 4> slicePlaneCorners(glm::dvec3 extent, glm::dvec3 spacing, int axis, int index) {
    const glm::ivec2 a = sliceImageAxes(axis);
    const int count = std::max(1, int(std::lround(extent[axis] / spacing[axis])));
    const double position = (std::clamp(index, 0, count - 1) + 0.5) * spacing[axis];
    std::array<glm::dvec3, 4> corners;
    // Walk the rectangle (0,0) (1,0) (1,1) (0,1) in the plane's two in-plane axes.
    const int walk[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int c = 0; c < 4; ++c) {
        glm::dvec3 p(0.0);
        p[axis] = position;
        p[a.x] = walk[c][0] * extent[a.x];
        p[a.y] = walk[c][1] * extent[a.y];
        corners[c] = p;
    }
    return corners;
}

std::vector<glm::dvec2> projectPolygon(const Camera& camera, const std::vector<glm::dvec3>& polygon) {
    const glm::dmat4 clipFromWorld(camera.clipFromWorld());
    std::vector<glm::dvec4> clip;
    clip.reserve(polygon.size());
    for (const glm::dvec3& p : polygon) clip.push_back(clipFromWorld * glm::dvec4(p, 1.0));

    // Sutherland-Hodgman against the single plane w >= near (orthographic w is
    // always 1, so nothing is clipped there). `near` is a tiny depth in world
    // units: the eye itself would divide by zero.
    const double near = 1e-6;
    std::vector<glm::dvec4> kept;
    for (std::size_t n = 0; n < clip.size(); ++n) {
        const glm::dvec4& a = clip[n];
        const glm::dvec4& b = clip[(n + 1) % clip.size()];
        const bool aIn = a.w >= near, bIn = b.w >= near;
        if (aIn) kept.push_back(a);
        if (aIn != bIn) kept.push_back(a + (b - a) * ((near - a.w) / (b.w - a.w)));
    }

    // NDC x in [-1, 1] spans the image width; NDC y points up, image rows down.
    std::vector<glm::dvec2> pixels;
    pixels.reserve(kept.size());
    for (const glm::dvec4& c : kept) {
        const glm::dvec2 ndc(c.x / c.w, c.y / c.w);
        pixels.emplace_back((ndc.x + 1.0) * 0.5 * camera.width, (1.0 - ndc.y) * 0.5 * camera.height);
    }
    return pixels;
}

std::vector<glm::dvec2> slicePlaneOutline(const Camera& camera, glm::dvec3 extent, glm::dvec3 spacing, int axis,
                                          int index) {
    const std::array<glm::dvec3, 4> corners = slicePlaneCorners(extent, spacing, axis, index);
    return projectPolygon(camera, std::vector<glm::dvec3>(corners.begin(), corners.end()));
}

}  // namespace voxlab
