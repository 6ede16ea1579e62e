// voxlab: the slice viewer, a Dear ImGui panel with the axial, coronal and
// sagittal slices through a shared crosshair voxel (orientations in
// orthogonal_slices.h), and the slice planes drawn over the 3D view.
//
// In a view:
//   left click / drag   moves the crosshair there (the other views follow)
//   scroll, arrow keys  move this view's slice by one voxel (wheel up, up and
//                       right arrows: +1); Page Up / Page Down by ten
//   right drag          window/level: right widens the window, up brightens
//                       (lowers the level); see dragWindow()
// The panel also has level and width drag fields, a reset to the volume's
// value range, "smooth" (bilinear display) and "z up" (off flips the coronal
// and sagittal views on screen) checkboxes, and a line with the voxel and
// value under the mouse (or at the crosshair), in data units. The controls
// wrap onto two lines in a narrow window.
//
// Each view is drawn with its pixels in the shape of the voxels (the spacing
// sets the aspect) and all three at the same scale, so that lengths compare
// across views. Frames, crosshair lines and 3D planes share each slice's
// colour (sliceAxisColour: sagittal red, coronal green, axial blue).
//
// Needs a current OpenGL 3.3 context (the viewer's) from the first draw until
// the SliceViewer is destroyed: it owns one texture per view, uploaded again
// only when that view's slice, window, volume or filtering changes.
#pragma once

#include <optional>

#include <imgui.h>

#include "voxlab/gl_object.h"
#include "voxlab/camera.h"
#include "voxlab/orthogonal_slices.h"
#include "voxlab/volume.h"

namespace voxlab {

class SliceViewer {
public:
    SliceViewer() = default;
    ~SliceViewer();  // frees the textures (the GL context must still be current)
    SliceViewer(const SliceViewer&) = delete;
    SliceViewer& operator=(const SliceViewer&) = delete;

    // Draws an ImGui window `title` with the three views. `open`, when given,
    // adds a close button. Returns true when the cursor (voxel or window) changed.
    bool draw(const char* title, const Volume& volume, SliceCursor* cursor, bool* open = nullptr);
    // The same contents inside the current ImGui window (for a tab or a panel),
    // filling the space that is left.
    bool drawContents(const Volume& volume, SliceCursor* cursor);

    // Forces the next draw to upload every view again (e.g. after loading a
    // new volume at the same address).
    void invalidate();

    // After a draw: where view `axis` put its image (screen coordinates), the
    // voxel under the mouse if any, and how many texture uploads there have been.
    ImVec2 imageMin(int axis) const { return views_[axis].imageMin; }
    ImVec2 imageMax(int axis) const { return views_[axis].imageMax; }
    std::optional<glm::ivec3> hoveredVoxel() const { return hovered_; }
    int uploadCount() const { return uploads_; }

    // Bilinear filtering of the slice images (off: each voxel is a sharp square).
    bool smooth = false;
    // One view alone, filling the panel (a double click on a view toggles
    // it), or -1: all three.
    int enlarged = -1;
    // Coronal and sagittal views with z growing upwards, as orthogonal_slices.h
    // states. Off flips them on screen (z grows downwards), which stands up
    // volumes stored from the top of the head down (cthead, headsq). Mouse and
    // crosshair follow the flip; the images and mappings of orthogonal_slices.h
    // do not change.
    bool zUp = true;

private:
    struct View {
        GlTexture texture;
        // What the texture holds; uploaded again when any of these differs.
        const void* data = nullptr;
        glm::ivec3 dims{0};
        int index = -1;
        glm::dvec2 window{0.0};
        bool smooth = false;
        ImVec2 imageMin{0, 0}, imageMax{0, 0};
    };

    void upload(View& view, const Volume& volume, int axis, int index, glm::dvec2 window);
    // The parts of drawContents (slice_viewer.cpp).
    void windowControls(SliceCursor* cursor, const glm::dvec2& range, double span);
    void placeView(int axis, const Volume& volume, float scale, ImVec2 cellMin, ImVec2 cellMax);
    void viewInput(int axis, const glm::ivec3& dims, SliceCursor* cursor, const glm::dvec2& range);
    void drawView(ImDrawList* list, int axis, const Volume& volume, const SliceCursor& cursor);
    void readout(const Volume& volume, const SliceCursor& cursor, ImVec2 at);
    // The screen row of an image row: coronal and sagittal rows run against
    // the image's when z grows downwards (zUp off).
    int displayRow(const glm::ivec3& dims, int axis, int row) const;
    bool shown(int axis) const { return enlarged < 0 || axis == enlarged; }

    View views_[3];
    std::optional<glm::ivec3> hovered_;
    int uploads_ = 0;
    float wheel_ = 0.0f;  // scroll left over between whole slice steps (touchpads)
};

// Draws the three slice planes through `voxel` over a 3D view: each plane's
// outline (with a faint fill) in its slice colour, and a dot at the
// crosshair. `camera` is the camera that rendered the image shown in the
// screen rectangle [viewportMin, viewportMax] (its width and height may
// differ from the rectangle's, e.g. a reduced-resolution render: the image is
// stretched to the rectangle). `extent` and `spacing` are the volume's.
void drawSlicePlanes(ImDrawList* list, const Camera& camera, glm::dvec3 extent, glm::dvec3 spacing,
                     glm::ivec3 voxel, ImVec2 viewportMin, ImVec2 viewportMax);

}  // namespace voxlab
