// voxlab: the three orthogonal slices of a volume (axial, coronal,
// sagittal) as 8-bit grey images with a window applied, the mapping between
// slice pixels and voxels, and the outlines of the slice planes as a camera
// sees them. Plain CPU code: the slice viewer (slice_viewer.h) draws these.
//
// A slice is named by the axis it is normal to, and holds every voxel whose
// index along that axis is `index`:
//
//   axis  name      index  image column u   image row v (down)  looks like
//   2     axial     k      i (x -> right)   j      (y -> down)  the "+z" axis view
//   1     coronal   j      i (x -> right)   nz-1-k (z -> up)
//   0     sagittal  i      j (y -> right)   nz-1-k (z -> up)
//
// So the axial image is exactly what the "+z" camera view shows, and the
// coronal and sagittal images stand upright with z growing upwards. Pixel
// (u, v) has its centre at (u + 1/2, v + 1/2) in continuous image
// coordinates, like camera images.
//
// Out-of-range indices (slice index, pixel, voxel) are clamped to the volume,
// never an error: the viewer's mouse and keys may point just outside. An axis
// other than 0, 1, 2 is a programming error and throws voxlab::Error.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/camera.h"
#include "voxlab/volume.h"

namespace voxlab {

constexpr int kSagittalAxis = 0;
constexpr int kCoronalAxis = 1;
constexpr int kAxialAxis = 2;

// "sagittal", "coronal", "axial".
const char* sliceAxisName(int axis);

// The colour that marks a slice everywhere (its view's frame, its crosshair
// line, its plane in the 3D view): sagittal red, coronal green, axial blue,
// i.e. the axis it is normal to as (x, y, z) -> (r, g, b). Linear RGB in [0, 1].
glm::vec3 sliceAxisColour(int axis);

// What the slice viewer shows: the crosshair voxel, through which all three
// slices pass, and the grey window in data units (values <= lo are black,
// >= hi white).
struct SliceCursor {
    glm::ivec3 voxel{0};
    glm::dvec2 window{0.0, 1.0};  // lo, hi
};

// The cursor a viewer starts from: the centre voxel and the volume's value range.
SliceCursor initialSliceCursor(const Volume& volume);

glm::ivec3 clampVoxel(glm::ivec3 voxel, glm::ivec3 dims);

// The volume axes that the image's columns (x) and rows (y) run along.
glm::ivec2 sliceImageAxes(int axis);

// Width and height of the slice image in pixels.
glm::ivec2 sliceImageSize(glm::ivec3 dims, int axis);

// Width and height of the slice in world units (pixel counts times spacing):
// the rectangle the viewer displays, so anisotropic voxels keep their shape.
glm::dvec2 sliceWorldSize(glm::ivec3 dims, glm::dvec3 spacing, int axis);

// Slice pixel (u, v) of slice `index` -> the voxel it shows, and back
// (slicePixel ignores voxel[axis]). Both clamp to the volume.
glm::ivec3 sliceVoxel(glm::ivec3 dims, int axis, int index, glm::ivec2 pixel);
glm::ivec2 slicePixel(glm::ivec3 dims, int axis, glm::ivec3 voxel);

// The 8-bit grey of a value under a window: round(clamp((v-lo)/(hi-lo), 0, 1) * 255).
// A window with hi <= lo is a threshold: 255 for v >= lo, 0 below.
std::uint8_t windowedGrey(double value, glm::dvec2 window);

// A slice as a grey image, rows top to bottom in the orientation above.
struct SliceImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> grey;  // width*height, row 0 at the top
    double pixelAspect = 1.0;        // height of a pixel / its width (spacing ratio)

    std::uint8_t at(int u, int v) const { return grey[std::size_t(v) * width + u]; }
};

// Slice `index` (clamped) along `axis` with `window` applied.
SliceImage extractSlice(const Volume& volume, int axis, int index, glm::dvec2 window);

// Window <-> level (centre) and width, all in data units.
inline double windowLevel(glm::dvec2 window) { return 0.5 * (window.x + window.y); }
inline double windowWidth(glm::dvec2 window) { return window.y - window.x; }
glm::dvec2 windowFromLevelWidth(double level, double width);

// The window after a right-button drag of (dx, dy) pixels: dragging right
// widens the window (less contrast), left narrows it; dragging up lowers the
// level (the image gets brighter), down raises it. 500 pixels of drag span the
// whole value range. The width never drops below 1/1000 of the range (nor
// below 1e-12), so the window stays valid.
glm::dvec2 dragWindow(glm::dvec2 window, double dx, double dy, glm::dvec2 valueRange);

// The plane of slice `index` along `axis` in world space: the rectangle where
// the plane through that slice's voxel centres, at (index + 1/2) * spacing,
// crosses the box [0, extent]. The index is clamped to the box. Corners in order
// around the rectangle.
std::array<glm::dvec3, 4> slicePlaneCorners(glm::dvec3 extent, glm::dvec3 spacing, int axis, int index);

// A world-space polygon projected into the camera's image, in continuous pixel
// coordinates (x right, y down; pixel (px, py) covers [px, px+1) x [py, py+1)),
// through Camera::clipFromWorld(). In perspective, the part behind the eye is
// clipped away first, so the result may have more or fewer points (none when
// everything is behind).
std::vector<glm::dvec2> projectPolygon(const Camera& camera, const std::vector<glm::dvec3>& polygon);

// The outline of slice `index` along `axis` in the camera's image.
std::vector<glm::dvec2> slicePlaneOutline(const Camera& camera, glm::dvec3 extent, glm::dvec3 spacing, int axis,
                                          int index);

}  // namespace voxlab
