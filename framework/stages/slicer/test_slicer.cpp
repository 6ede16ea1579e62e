// The slicer: at a plane through voxel centres it must reproduce that slice
// of the volume exactly (nearest and trilinear alike, since trilinear
// weights vanish at voxel centres), in every axis view. The expected slice is
// read straight from the voxels here.
#include <gtest/gtest.h>

#include <cmath>

#include "support/axis_views.h"
#include "support/gl_fixture.h"

namespace voxlab::testing {
namespace {


// The slicer's `offset` (in smallest spacings, along the view direction)
// that puts the plane through the centres of voxel layer k on the view axis.
double offsetForLayer(const Volume& v, const AxisView& view, int k) {
    const int a = view.fwdAxis;
    const double planeWorld = (k + 0.5) * v.spacing()[a];
    return view.fwdSign * (planeWorld - v.extent()[a] / 2.0) / v.minSpacing();
}

void expectSlice(const std::vector<int>& got, const Volume& v, const AxisView& view, int k, int width) {
    const int height = v.dims()[view.downAxis];
    const double lo = v.minValue(), hi = v.maxValue();
    int bad = 0;
    std::string first;
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            glm::ivec3 ijk;
            ijk[view.fwdAxis] = k;
            ijk[view.rightAxis] = view.rightSign > 0 ? px : v.dims()[view.rightAxis] - 1 - px;
            ijk[view.downAxis] = view.downSign > 0 ? py : v.dims()[view.downAxis] - 1 - py;
            const double g = std::clamp((v.value(ijk.x, ijk.y, ijk.z) - lo) / (hi - lo), 0.0, 1.0);
            const int want = int(std::lround(g * 255.0));
            const int have = got[std::size_t(py) * width + px];
            if (std::abs(want - have) > 1 && bad++ == 0)
                first = "pixel (" + std::to_string(px) + "," + std::to_string(py) + "): got " +
                        std::to_string(have) + ", voxel gives " + std::to_string(want);
        }
    EXPECT_EQ(bad, 0) << first;
}

class SlicerLayers : public GlTest, public ::testing::WithParamInterface<Interpolation> {};

TEST_P(SlicerLayers, VoxelCentrePlaneReproducesTheSlice) {
    // tooth is non-cubic (103x94x161); with isotropic spacing the image size
    // equal to the slice's dimensions puts pixel centres on voxel centres.
    const Volume v = loadVolume(datasetPath("tooth.nrrd"));
    for (const AxisView& view : kAxisViews) {
        const int n = v.dims()[view.fwdAxis];
        for (int k : {0, n / 3, n / 2, n - 1}) {
            SCOPED_TRACE(std::string("view ") + view.name + ", layer " + std::to_string(k));
            Scene scene;
            scene.renderer = "slicer";
            scene.camera.view = view.name;
            scene.camera.projection = Projection::Orthographic;
            scene.width = v.dims()[view.rightAxis];
            scene.height = v.dims()[view.downAxis];
            scene.interpolation = GetParam();
            scene.parameters["offset"] = offsetForLayer(v, view, k);
            expectSlice(renderGrey(v, scene), v, view, k, scene.width);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Interpolations, SlicerLayers,
                         ::testing::Values(Interpolation::Nearest, Interpolation::Trilinear),
                         [](const auto& info) { return std::string(interpolationName(info.param)); });

// Between two layers, trilinear interpolation gives their average.
TEST_F(GlTest, SlicerHalfwayBetweenLayersAveragesThem) {
    const Volume v = loadVolume(datasetPath("bucky.nrrd"));
    const AxisView& view = kAxisViews[0];  // +z
    Scene scene;
    scene.renderer = "slicer";
    scene.camera.view = "+z";
    scene.camera.projection = Projection::Orthographic;
    scene.width = v.dims().x, scene.height = v.dims().y;
    scene.interpolation = Interpolation::Trilinear;
    scene.window = glm::dvec2(0.0, 255.0);
    const int k = 10;
    scene.parameters["offset"] = (offsetForLayer(v, view, k) + offsetForLayer(v, view, k + 1)) / 2.0;
    const std::vector<int> got = renderGrey(v, scene);
    int bad = 0;
    for (int y = 0; y < v.dims().y; ++y)
        for (int x = 0; x < v.dims().x; ++x) {
            const double want = (v.value(x, y, k) + v.value(x, y, k + 1)) / 2.0;
            if (std::abs(got[std::size_t(y) * v.dims().x + x] - want) > 1.01) ++bad;
        }
    EXPECT_EQ(bad, 0);
}

// A plane moved outside the box shows only background.
TEST_F(GlTest, SlicerOutsideTheVolumeIsEmpty) {
    const Volume v = makePhantom("phantom:shells:32");
    Scene scene;
    scene.renderer = "slicer";
    scene.camera.view = "+x";
    scene.camera.projection = Projection::Orthographic;
    scene.width = scene.height = 32;
    scene.parameters["offset"] = 20.0;  // half the box is 16
    for (int g : renderGrey(v, scene)) ASSERT_EQ(g, 0);
}

}  // namespace
}  // namespace voxlab::testing
