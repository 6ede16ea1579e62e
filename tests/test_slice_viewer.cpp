// The slice viewer: slices as windowed grey images in the orientations that
// orthogonal_slices.h states, the pixel <-> voxel mapping, the window drag,
// the slice planes projected by a camera (checked against Camera::ray), and
// the ImGui panel driven headlessly (clicks, scroll, keys, right-drag).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "voxlab/error.h"
#include "voxlab/orthogonal_slices.h"

#ifdef VOXLAB_HAVE_VIEWER
#include "voxlab_gl.h"

#include <imgui.h>

#include "voxlab/gl_context.h"
#include "voxlab/slice_viewer.h"
#endif

namespace voxlab {
namespace {

// A uint8 volume whose value is its linear voxel index i + nx (j + ny k):
// every voxel is distinguishable, and with the window (0, 255) a grey level
// is exactly the value (dims chosen so that the count stays <= 256).
Volume indexVolume(glm::ivec3 dims, glm::dvec3 spacing) {
    std::vector<std::uint8_t> bytes(std::size_t(dims.x) * dims.y * dims.z);
    for (std::size_t n = 0; n < bytes.size(); ++n) bytes[n] = std::uint8_t(n);
    return Volume(dims, VoxelType::UInt8, spacing, std::move(bytes), "index");
}

int linearIndex(glm::ivec3 dims, int i, int j, int k) { return i + dims.x * (j + dims.y * k); }

// A float32 volume of random values in [-0.25, 1.25].
Volume randomVolume(glm::ivec3 dims, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(-0.25f, 1.25f);
    std::vector<std::uint8_t> bytes(std::size_t(dims.x) * dims.y * dims.z * 4);
    for (std::size_t n = 0; n < bytes.size(); n += 4) {
        const float f = dist(rng);
        std::memcpy(&bytes[n], &f, 4);
    }
    return Volume(dims, VoxelType::Float32, glm::dvec3(1.0), std::move(bytes), "random");
}

TEST(OrthogonalSlices, AxialShowsXRightYDown) {
    const glm::ivec3 d(5, 4, 6);  // 120 voxels
    const Volume v = indexVolume(d, glm::dvec3(1.0));
    for (int k : {0, 2, 5}) {
        const SliceImage img = extractSlice(v, kAxialAxis, k, {0.0, 255.0});
        ASSERT_EQ(img.width, d.x);
        ASSERT_EQ(img.height, d.y);
        for (int row = 0; row < img.height; ++row)
            for (int col = 0; col < img.width; ++col)
                ASSERT_EQ(img.at(col, row), linearIndex(d, col, row, k)) << "k " << k << " pixel " << col << "," << row;
    }
}

TEST(OrthogonalSlices, CoronalShowsXRightZUp) {
    const glm::ivec3 d(5, 4, 6);
    const Volume v = indexVolume(d, glm::dvec3(1.0));
    for (int j : {0, 3}) {
        const SliceImage img = extractSlice(v, kCoronalAxis, j, {0.0, 255.0});
        ASSERT_EQ(img.width, d.x);
        ASSERT_EQ(img.height, d.z);
        for (int row = 0; row < img.height; ++row)
            for (int col = 0; col < img.width; ++col)
                ASSERT_EQ(img.at(col, row), linearIndex(d, col, j, d.z - 1 - row)) << "j " << j;
    }
}

TEST(OrthogonalSlices, SagittalShowsYRightZUp) {
    const glm::ivec3 d(5, 4, 6);
    const Volume v = indexVolume(d, glm::dvec3(1.0));
    for (int i : {0, 4}) {
        const SliceImage img = extractSlice(v, kSagittalAxis, i, {0.0, 255.0});
        ASSERT_EQ(img.width, d.y);
        ASSERT_EQ(img.height, d.z);
        for (int row = 0; row < img.height; ++row)
            for (int col = 0; col < img.width; ++col)
                ASSERT_EQ(img.at(col, row), linearIndex(d, i, col, d.z - 1 - row)) << "i " << i;
    }
}

TEST(OrthogonalSlices, WindowMapsValuesToGrey) {
    const glm::ivec3 d(7, 6, 5);
    const Volume v = randomVolume(d, 7);
    const glm::dvec2 window(0.2, 0.7);
    int below = 0, above = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const int index = d[axis] / 2;
        const SliceImage img = extractSlice(v, axis, index, window);
        for (int row = 0; row < img.height; ++row)
            for (int col = 0; col < img.width; ++col) {
                // The voxel from the orientation table, written out per axis.
                const int u = col, zUp = d.z - 1 - row;
                const double value = axis == kAxialAxis     ? v.value(u, row, index)
                                     : axis == kCoronalAxis ? v.value(u, index, zUp)
                                                            : v.value(index, u, zUp);
                const double t = std::min(1.0, std::max(0.0, (value - window.x) / (window.y - window.x)));
                below += value < window.x, above += value > window.y;
                // Exact: the same rounding of the same double, no tolerance.
                ASSERT_EQ(int(img.at(col, row)), int(std::lround(t * 255.0))) << "axis " << axis;
            }
    }
    EXPECT_GT(below, 0);  // the clamps were exercised
    EXPECT_GT(above, 0);
}

TEST(OrthogonalSlices, WindowEdgesAndThreshold) {
    EXPECT_EQ(windowedGrey(10.0, {10.0, 20.0}), 0);
    EXPECT_EQ(windowedGrey(20.0, {10.0, 20.0}), 255);
    EXPECT_EQ(windowedGrey(15.0, {10.0, 20.0}), 128);  // 127.5 rounds away from zero
    EXPECT_EQ(windowedGrey(-1e9, {10.0, 20.0}), 0);
    EXPECT_EQ(windowedGrey(1e9, {10.0, 20.0}), 255);
    // An empty window is a threshold at lo.
    EXPECT_EQ(windowedGrey(4.999, {5.0, 5.0}), 0);
    EXPECT_EQ(windowedGrey(5.0, {5.0, 5.0}), 255);
}

TEST(OrthogonalSlices, SpacingSetsPixelAspectAndWorldSize) {
    const glm::ivec3 d(5, 4, 6);
    const glm::dvec3 s(1.0, 2.0, 3.0);
    const Volume v = indexVolume(d, s);
    // Height of a pixel over its width: the spacing along the rows' axis over the columns'.
    EXPECT_DOUBLE_EQ(extractSlice(v, kAxialAxis, 0, {0, 255}).pixelAspect, 2.0 / 1.0);
    EXPECT_DOUBLE_EQ(extractSlice(v, kCoronalAxis, 0, {0, 255}).pixelAspect, 3.0 / 1.0);
    EXPECT_DOUBLE_EQ(extractSlice(v, kSagittalAxis, 0, {0, 255}).pixelAspect, 3.0 / 2.0);
    EXPECT_EQ(sliceWorldSize(d, s, kAxialAxis), glm::dvec2(5.0, 8.0));
    EXPECT_EQ(sliceWorldSize(d, s, kCoronalAxis), glm::dvec2(5.0, 18.0));
    EXPECT_EQ(sliceWorldSize(d, s, kSagittalAxis), glm::dvec2(8.0, 18.0));
}

TEST(OrthogonalSlices, PixelVoxelRoundTrips) {
    const glm::ivec3 d(5, 4, 6);
    for (int axis = 0; axis < 3; ++axis) {
        const glm::ivec2 size = sliceImageSize(d, axis);
        for (int index = 0; index < d[axis]; ++index)
            for (int row = 0; row < size.y; ++row)
                for (int col = 0; col < size.x; ++col) {
                    const glm::ivec3 voxel = sliceVoxel(d, axis, index, {col, row});
                    ASSERT_EQ(voxel[axis], index);
                    ASSERT_EQ(slicePixel(d, axis, voxel), glm::ivec2(col, row)) << "axis " << axis;
                }
        // And the other way: every voxel is shown by exactly the pixel that maps back to it.
        for (int k = 0; k < d.z; ++k)
            for (int j = 0; j < d.y; ++j)
                for (int i = 0; i < d.x; ++i) {
                    const glm::ivec3 voxel(i, j, k);
                    ASSERT_EQ(sliceVoxel(d, axis, voxel[axis], slicePixel(d, axis, voxel)), voxel);
                }
    }
}

TEST(OrthogonalSlices, OutOfRangeIsClampedAndABadAxisThrows) {
    const glm::ivec3 d(5, 4, 6);
    const Volume v = indexVolume(d, glm::dvec3(1.0));
    EXPECT_EQ(extractSlice(v, kAxialAxis, -3, {0, 255}).grey, extractSlice(v, kAxialAxis, 0, {0, 255}).grey);
    EXPECT_EQ(extractSlice(v, kAxialAxis, 99, {0, 255}).grey, extractSlice(v, kAxialAxis, 5, {0, 255}).grey);
    EXPECT_NE(extractSlice(v, kAxialAxis, 0, {0, 255}).grey, extractSlice(v, kAxialAxis, 5, {0, 255}).grey);
    // Axial pixel (-1, 9) is past the left and bottom edges: voxel (0, ny-1).
    EXPECT_EQ(sliceVoxel(d, kAxialAxis, 2, {-1, 9}), glm::ivec3(0, 3, 2));
    // Coronal row -4 is above the top, i.e. the highest z.
    EXPECT_EQ(sliceVoxel(d, kCoronalAxis, 7, {9, -4}), glm::ivec3(4, 3, 5));
    EXPECT_EQ(slicePixel(d, kSagittalAxis, {0, -2, 10}), glm::ivec2(0, 0));
    EXPECT_EQ(clampVoxel({-1, 2, 6}, d), glm::ivec3(0, 2, 5));
    EXPECT_THROW(extractSlice(v, 3, 0, {0, 255}), Error);
    EXPECT_THROW(sliceVoxel(d, -1, 0, {0, 0}), Error);
}

TEST(OrthogonalSlices, InitialCursorIsTheCentreAndTheValueRange) {
    const Volume v = randomVolume({7, 6, 5}, 3);
    const SliceCursor c = initialSliceCursor(v);
    EXPECT_EQ(c.voxel, glm::ivec3(3, 3, 2));
    EXPECT_EQ(c.window, v.valueRange());
}

TEST(OrthogonalSlices, DragWindowWidensRightAndBrightensUp) {
    const glm::dvec2 range(0.0, 1000.0), window(400.0, 600.0);  // level 500, width 200
    // 500 px of drag span the range: 2 data units per pixel.
    const glm::dvec2 wider = dragWindow(window, 50.0, 0.0, range);
    EXPECT_DOUBLE_EQ(windowWidth(wider), 300.0);
    EXPECT_DOUBLE_EQ(windowLevel(wider), 500.0);
    const glm::dvec2 up = dragWindow(window, 0.0, -25.0, range);  // screen y grows down
    EXPECT_DOUBLE_EQ(windowLevel(up), 450.0);
    EXPECT_DOUBLE_EQ(windowWidth(up), 200.0);
    // Narrowing stops at 1/1000 of the range.
    EXPECT_DOUBLE_EQ(windowWidth(dragWindow(window, -1000.0, 0.0, range)), 1.0);
    EXPECT_EQ(windowFromLevelWidth(500.0, 200.0), window);
}

// --- slice planes through a camera -------------------------------------------------------------------------------

TEST(SlicePlanes, CornersLieOnTheVoxelCentrePlaneAcrossTheBox) {
    const glm::dvec3 spacing(1.0, 2.0, 0.5), extent = glm::dvec3(10, 6, 8) * spacing;
    const auto c = slicePlaneCorners(extent, spacing, kCoronalAxis, 2);
    for (const glm::dvec3& p : c) EXPECT_DOUBLE_EQ(p.y, 2.5 * 2.0);
    EXPECT_EQ(c[0], glm::dvec3(0.0, 5.0, 0.0));
    EXPECT_EQ(c[2], glm::dvec3(10.0, 5.0, 4.0));  // the opposite corner
    // Clamped like the slices: index 99 is the last layer.
    EXPECT_DOUBLE_EQ(slicePlaneCorners(extent, spacing, kCoronalAxis, 99)[0].y, 5.5 * 2.0);
}

TEST(SlicePlanes, PlusZViewSeesTheAxialPlaneAsTheWholeBoxAndTheOthersAsLines) {
    // With the image the size of the slice in voxels (spacing 1), pixel
    // centres sit on voxel centres, so pixel edges are voxel faces.
    const glm::ivec3 d(24, 16, 10);
    const glm::dvec3 extent(d);
    CameraSpec spec;
    spec.view = "+z";
    spec.projection = Projection::Orthographic;
    const Camera cam = Camera::make(spec, extent, d.x, d.y);
    const double tol = 1e-3;  // pixels: clipFromWorld is a float matrix (~1e-7 relative of ~24 px)

    const auto axial = slicePlaneOutline(cam, extent, glm::dvec3(1.0), kAxialAxis, 3);
    ASSERT_EQ(axial.size(), 4u);
    const glm::dvec2 want[4] = {{0, 0}, {24, 0}, {24, 16}, {0, 16}};
    for (int n = 0; n < 4; ++n) {
        EXPECT_NEAR(axial[n].x, want[n].x, tol) << n;
        EXPECT_NEAR(axial[n].y, want[n].y, tol) << n;
    }
    // Sagittal plane at i = 7: a vertical line through the centres of pixel column 7.
    const auto sagittal = slicePlaneOutline(cam, extent, glm::dvec3(1.0), kSagittalAxis, 7);
    ASSERT_EQ(sagittal.size(), 4u);
    double top = 1e9, bottom = -1e9;
    for (const glm::dvec2& p : sagittal) {
        EXPECT_NEAR(p.x, 7.5, tol);
        top = std::min(top, p.y), bottom = std::max(bottom, p.y);
    }
    EXPECT_NEAR(top, 0.0, tol);
    EXPECT_NEAR(bottom, 16.0, tol);
    // Coronal plane at j = 12: a horizontal line through row 12 (y grows down in the +z view).
    for (const glm::dvec2& p : slicePlaneOutline(cam, extent, glm::dvec3(1.0), kCoronalAxis, 12))
        EXPECT_NEAR(p.y, 12.5, tol);
}

TEST(SlicePlanes, ProjectedCornersLieOnTheCameraRays) {
    // Independent oracle: Camera::ray through each projected point must pass
    // through the world corner it came from (an orbit view, perspective and
    // orthographic, anisotropic spacing, a non-square image).
    const glm::ivec3 d(64, 64, 93);
    const glm::dvec3 spacing(3.2, 3.2, 1.5), extent = glm::dvec3(d) * spacing;
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        CameraSpec spec;
        spec.azimuth = 37.0, spec.elevation = -24.0, spec.zoom = 1.3;
        spec.projection = projection;
        const Camera cam = Camera::make(spec, extent, 320, 200);
        for (int axis = 0; axis < 3; ++axis) {
            const auto corners = slicePlaneCorners(extent, spacing, axis, d[axis] / 3);
            const auto pixels = slicePlaneOutline(cam, extent, spacing, axis, d[axis] / 3);
            ASSERT_EQ(pixels.size(), 4u);
            for (int n = 0; n < 4; ++n) {
                glm::dvec3 origin, direction;
                cam.ray(pixels[n].x, pixels[n].y, &origin, &direction);
                const glm::dvec3 q = corners[n] - origin;
                const double miss = glm::length(q - glm::dot(q, direction) * direction);
                // World units; the box is ~200 units across, the float matrix
                // carries ~1e-7 relative error, so 1e-3 is generous yet a
                // pixel off (~1 unit here) fails.
                EXPECT_LT(miss, 1e-3) << projectionName(projection) << " axis " << axis << " corner " << n;
            }
        }
    }
}

TEST(SlicePlanes, PerspectiveClipsWhatIsBehindTheEye) {
    const glm::dvec3 extent(10.0);
    CameraSpec spec;
    spec.view = "+z";
    spec.projection = Projection::Perspective;
    Camera cam = Camera::make(spec, extent, 100, 100);
    cam.position = glm::dvec3(5.0, 5.0, 5.0);  // the eye inside the box, looking along +z
    // A plane entirely behind the eye vanishes; one entirely in front keeps its 4 corners.
    EXPECT_TRUE(projectPolygon(cam, {{0, 0, 1}, {10, 0, 1}, {10, 10, 1}, {0, 10, 1}}).empty());
    EXPECT_EQ(projectPolygon(cam, {{0, 0, 9}, {10, 0, 9}, {10, 10, 9}, {0, 10, 9}}).size(), 4u);
    // A plane through the eye's depth (the sagittal x = 2 plane, z from 0 to 10)
    // keeps its front half: 4 points, every one in front of (not behind) the eye,
    // i.e. on the right side of the image's left edge (x = 2 is left of the eye).
    const auto clipped = projectPolygon(cam, {{2, 0, 0}, {2, 10, 0}, {2, 10, 10}, {2, 0, 10}});
    ASSERT_EQ(clipped.size(), 4u);
    for (const glm::dvec2& p : clipped) EXPECT_LT(p.x, 50.0);
}

#ifdef VOXLAB_HAVE_VIEWER
// --- the ImGui panel, headless ------------------------------------------------------------------------------------

// One ImGui context (no platform or renderer backend: nothing is drawn, draw
// lists are only built) on a headless GL context for the textures.
class SliceViewerUi : public ::testing::Test {
protected:
    void SetUp() override {
        gl_ = createHeadlessContext();
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(900, 800);
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels;
        int w, h;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        // Keys as a backend would map them (ImGui 1.86: indices into io.KeysDown).
        io.KeyMap[ImGuiKey_UpArrow] = 1;
        io.KeyMap[ImGuiKey_DownArrow] = 2;
        io.KeyMap[ImGuiKey_LeftArrow] = 3;
        io.KeyMap[ImGuiKey_RightArrow] = 4;
        io.KeyMap[ImGuiKey_PageUp] = 5;
        io.KeyMap[ImGuiKey_PageDown] = 6;
    }
    void TearDown() override {
        viewer_.reset();  // frees the textures while the GL context lives
        ImGui::DestroyContext();
        gl_.reset();
    }

    static ImGuiIO& io() { return ImGui::GetIO(); }

    // One frame with the mouse at `mouse`; returns what draw() returned.
    bool frame(ImVec2 mouse, bool left = false, bool right = false, float wheel = 0.0f, int key = -1) {
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = mouse;
        io.MouseDown[0] = left;
        io.MouseDown[1] = right;
        io.MouseWheel = wheel;
        for (bool& k : io.KeysDown) k = false;
        if (key >= 0) io.KeysDown[key] = true;
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(0, 0));
        const bool changed = viewer_->draw("slices", volume_, &cursor_);
        ImGui::Render();
        return changed;
    }
    // The screen position of the centre of slice pixel (u, v) in view `axis`.
    ImVec2 pixelCentre(int axis, int u, int v) const {
        const glm::ivec2 size = sliceImageSize(volume_.dims(), axis);
        const ImVec2 a = viewer_->imageMin(axis), b = viewer_->imageMax(axis);
        return ImVec2(a.x + (u + 0.5f) * (b.x - a.x) / size.x, a.y + (v + 0.5f) * (b.y - a.y) / size.y);
    }
    // A click: move there, press, release.
    bool click(ImVec2 at) {
        frame(at);
        const bool changed = frame(at, true);
        frame(at);
        return changed;
    }

    std::unique_ptr<GlContext> gl_;
    std::unique_ptr<SliceViewer> viewer_ = std::make_unique<SliceViewer>();
    // 20 x 16 x 12 voxels, anisotropic; values 0..255 cycle through the index.
    Volume volume_ = [] {
        const glm::ivec3 d(20, 16, 12);
        std::vector<std::uint8_t> bytes(std::size_t(d.x) * d.y * d.z);
        for (std::size_t n = 0; n < bytes.size(); ++n) bytes[n] = std::uint8_t(n * 7);
        return Volume(d, VoxelType::UInt8, glm::dvec3(1.0, 1.5, 2.0), std::move(bytes), "ui");
    }();
    SliceCursor cursor_ = initialSliceCursor(volume_);
};

TEST_F(SliceViewerUi, ViewsKeepTheSliceShapesAndOneScale) {
    frame(ImVec2(-100, -100));
    frame(ImVec2(-100, -100));
    double scale = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        const glm::dvec2 world = sliceWorldSize(volume_.dims(), volume_.spacing(), axis);
        const ImVec2 a = viewer_->imageMin(axis), b = viewer_->imageMax(axis);
        ASSERT_GT(b.x - a.x, 50.0f) << axis;
        // Sizes are rounded to whole screen pixels: within 1 px of one common scale.
        if (axis == 0) scale = (b.x - a.x) / world.x;
        EXPECT_NEAR(b.x - a.x, world.x * scale, 1.0) << axis;
        EXPECT_NEAR(b.y - a.y, world.y * scale, 1.0) << axis;
        for (int other = 0; other < axis; ++other) {  // no overlap
            const ImVec2 c = viewer_->imageMin(other), e = viewer_->imageMax(other);
            EXPECT_TRUE(a.x >= e.x || b.x <= c.x || a.y >= e.y || b.y <= c.y) << axis << " vs " << other;
        }
    }
}

TEST_F(SliceViewerUi, TexturesHoldTheSlicesAndUploadOnlyOnChange) {
    frame(ImVec2(-100, -100));
    EXPECT_EQ(viewer_->uploadCount(), 3);
    for (int n = 0; n < 5; ++n) frame(ImVec2(-100, -100));
    EXPECT_EQ(viewer_->uploadCount(), 3);  // idle frames upload nothing
    // The images drawn, in the order drawn (sagittal, coronal, axial), hold
    // those slices: read back from GL.
    std::vector<GLuint> textures;
    const ImDrawData* data = ImGui::GetDrawData();
    ASSERT_NE(data, nullptr);
    for (int n = 0; n < data->CmdListsCount; ++n)
        for (const ImDrawCmd& cmd : data->CmdLists[n]->CmdBuffer)
            if (cmd.TextureId != ImGui::GetIO().Fonts->TexID) textures.push_back(GLuint(std::intptr_t(cmd.TextureId)));
    ASSERT_EQ(textures.size(), 3u);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    for (int axis = 0; axis < 3; ++axis) {
        const SliceImage want = extractSlice(volume_, axis, cursor_.voxel[axis], cursor_.window);
        glBindTexture(GL_TEXTURE_2D, textures[axis]);
        GLint width = 0, height = 0;
        glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
        glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &height);
        ASSERT_EQ(width, want.width) << sliceAxisName(axis);
        ASSERT_EQ(height, want.height) << sliceAxisName(axis);
        std::vector<std::uint8_t> got(want.grey.size());
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_UNSIGNED_BYTE, got.data());
        EXPECT_EQ(got, want.grey) << sliceAxisName(axis);
    }
}

TEST_F(SliceViewerUi, ClickingMovesTheCrosshairInThatViewsPlane) {
    frame(ImVec2(-100, -100));
    const glm::ivec3 start = cursor_.voxel;
    // Axial pixel (5, 7) is voxel (5, 7, k).
    EXPECT_TRUE(click(pixelCentre(kAxialAxis, 5, 7)));
    EXPECT_EQ(cursor_.voxel, glm::ivec3(5, 7, start.z));
    // Only the two slices through the new crosshair are uploaded again.
    EXPECT_EQ(viewer_->uploadCount(), 5);
    // Coronal pixel (u, v) is voxel (u, j, nz-1-v).
    click(pixelCentre(kCoronalAxis, 13, 2));
    EXPECT_EQ(cursor_.voxel, glm::ivec3(13, 7, 12 - 1 - 2));
    // Sagittal pixel (u, v) is voxel (i, u, nz-1-v).
    click(pixelCentre(kSagittalAxis, 4, 10));
    EXPECT_EQ(cursor_.voxel, glm::ivec3(13, 4, 1));
    // The mouse readout names the voxel under the mouse.
    frame(pixelCentre(kAxialAxis, 18, 3));
    ASSERT_TRUE(viewer_->hoveredVoxel().has_value());
    EXPECT_EQ(*viewer_->hoveredVoxel(), glm::ivec3(18, 3, 1));
    frame(ImVec2(-100, -100));
    EXPECT_FALSE(viewer_->hoveredVoxel().has_value());
}

TEST_F(SliceViewerUi, WithZDownTheScreenRowsCountKUpwards) {
    viewer_->zUp = false;
    frame(ImVec2(-100, -100));
    // The screen's row r from the top of the coronal view is now k = r.
    click(pixelCentre(kCoronalAxis, 13, 2));
    EXPECT_EQ(cursor_.voxel, glm::ivec3(13, 8, 2));
    click(pixelCentre(kSagittalAxis, 4, 10));
    EXPECT_EQ(cursor_.voxel, glm::ivec3(13, 4, 10));
    // The axial view is not flipped.
    click(pixelCentre(kAxialAxis, 5, 7));
    EXPECT_EQ(cursor_.voxel, glm::ivec3(5, 7, 10));
    // The texture is the same image, drawn upside down: its first row at the screen's bottom.
    ImDrawData* data = ImGui::GetDrawData();
    bool sawFlipped = false;
    for (int n = 0; n < data->CmdListsCount; ++n) {
        const ImDrawList* list = data->CmdLists[n];
        for (const ImDrawVert& v : list->VtxBuffer)
            if (v.pos.y == viewer_->imageMin(kCoronalAxis).y && v.pos.x == viewer_->imageMin(kCoronalAxis).x &&
                v.uv.y == 1.0f)
                sawFlipped = true;
    }
    EXPECT_TRUE(sawFlipped);
}

TEST_F(SliceViewerUi, ScrollAndArrowsMoveTheHoveredViewsSlice) {
    frame(ImVec2(-100, -100));
    const glm::ivec3 start = cursor_.voxel;
    const ImVec2 coronal = pixelCentre(kCoronalAxis, 1, 1);
    frame(coronal);
    EXPECT_TRUE(frame(coronal, false, false, 1.0f));
    EXPECT_EQ(cursor_.voxel, start + glm::ivec3(0, 1, 0));
    frame(coronal, false, false, -1.0f);
    frame(coronal, false, false, -1.0f);
    EXPECT_EQ(cursor_.voxel, start + glm::ivec3(0, -1, 0));
    const ImVec2 sagittal = pixelCentre(kSagittalAxis, 1, 1);
    frame(sagittal);
    frame(sagittal, false, false, 0.0f, io().KeyMap[ImGuiKey_UpArrow]);
    frame(sagittal);
    EXPECT_EQ(cursor_.voxel.x, start.x + 1);
    frame(sagittal, false, false, 0.0f, io().KeyMap[ImGuiKey_PageDown]);
    frame(sagittal);
    EXPECT_EQ(cursor_.voxel.x, start.x + 1 - 10);
    frame(sagittal, false, false, 0.0f, io().KeyMap[ImGuiKey_PageDown]);
    frame(sagittal);
    EXPECT_EQ(cursor_.voxel.x, 0);  // 10 more would pass the first slice: clamped
    // Scrolling off the end stays on the last slice.
    const ImVec2 axial = pixelCentre(kAxialAxis, 1, 1);
    for (int n = 0; n < 20; ++n) frame(axial, false, false, 1.0f);
    EXPECT_EQ(cursor_.voxel.z, 11);
}

TEST_F(SliceViewerUi, RightDragChangesWindowAndLevel) {
    frame(ImVec2(-100, -100));
    const glm::dvec2 start = cursor_.window;  // the value range, 0 .. 255 (or less)
    const double range = volume_.maxValue() - volume_.minValue();
    const ImVec2 at = pixelCentre(kAxialAxis, 10, 8);
    frame(at);
    frame(at, false, true);
    frame(ImVec2(at.x + 40, at.y), false, true);  // 40 px right
    frame(ImVec2(at.x + 40, at.y - 30), false, true);  // then 30 px up
    frame(ImVec2(at.x + 40, at.y - 30));
    // 500 px span the range. Tolerance: float mouse coordinates, ~1e-6 of the range.
    EXPECT_NEAR(windowWidth(cursor_.window), windowWidth(start) + 40 * range / 500, 1e-6 * range);
    EXPECT_NEAR(windowLevel(cursor_.window), windowLevel(start) - 30 * range / 500, 1e-6 * range);
    EXPECT_EQ(cursor_.voxel, initialSliceCursor(volume_).voxel);  // the right button leaves the crosshair
}

TEST_F(SliceViewerUi, AnOutOfRangeCursorIsClampedAndReported) {
    cursor_.voxel = glm::ivec3(50, -3, 11);
    EXPECT_TRUE(frame(ImVec2(-100, -100)));
    EXPECT_EQ(cursor_.voxel, glm::ivec3(19, 0, 11));
    EXPECT_FALSE(frame(ImVec2(-100, -100)));
}

TEST_F(SliceViewerUi, SlicePlanesDrawOverAViewport) {
    // The overlay draws each plane's outline: three closed polylines with
    // vertices inside the viewport (+z view: the axial plane fills it).
    ImGui::NewFrame();
    ImDrawList* list = ImGui::GetForegroundDrawList();
    const std::size_t before = list->VtxBuffer.Size;
    CameraSpec spec;
    spec.view = "+z";
    spec.projection = Projection::Orthographic;
    const Camera cam = Camera::make(spec, volume_.extent(), 200, 100);
    drawSlicePlanes(list, cam, volume_.extent(), volume_.spacing(), cursor_.voxel, ImVec2(100, 50), ImVec2(500, 250));
    EXPECT_GT(std::size_t(list->VtxBuffer.Size), before);
    for (int n = int(before); n < list->VtxBuffer.Size; ++n) {
        // Anti-aliased strokes fringe out by about a pixel.
        EXPECT_GE(list->VtxBuffer[n].pos.x, 100.0f - 3.0f);
        EXPECT_LE(list->VtxBuffer[n].pos.x, 500.0f + 3.0f);
    }
    ImGui::Render();
}
#endif

}  // namespace
}  // namespace voxlab
