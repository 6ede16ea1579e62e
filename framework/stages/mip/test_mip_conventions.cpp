// The rendering conventions, checked through the MIP renderer against CPU
// math written here: for every axis view, an orthographic MIP with nearest
// interpolation must equal the maximum over the view axis of the voxels that
// each pixel centre covers, within 1/255. Real datasets cover the awkward
// cases: non-cubic (tooth, silicium), 16-bit (cthead, stent), signed and
// anisotropic (headsq), float (a phantom).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "support/axis_columns.h"
#include "support/gl_fixture.h"

namespace voxlab::testing {
namespace {


struct Expected {
    // Acceptable grey levels per pixel: one, or two when the pixel centre
    // sits on a voxel boundary (nearest may then pick either neighbour).
    std::vector<std::vector<int>> grey;
    int ambiguous = 0;
};

Expected cpuMip(const Volume& v, const AxisView& view, int width, int height) {
    const glm::dvec3 ext = v.extent();
    const double er = ext[view.rightAxis], ed = ext[view.downAxis];
    // Uniform scale that fits the projected rectangle, centred.
    const double worldPerPixel = std::max(er / width, ed / height);
    const double lo = v.minValue(), hi = v.maxValue();
    Expected e;
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            // Offsets from the image centre, along image right and down.
            const double r = (px + 0.5 - width / 2.0) * worldPerPixel;
            const double d = (py + 0.5 - height / 2.0) * worldPerPixel;
            const double wr = ext[view.rightAxis] / 2 + view.rightSign * r;
            const double wd = ext[view.downAxis] / 2 + view.downSign * d;
            const std::vector<int> irs = voxelCandidates(v, view.rightAxis, wr);
            const std::vector<int> ids = voxelCandidates(v, view.downAxis, wd);
            std::vector<int> greys;
            for (int ir : irs)
                for (int id : ids) {
                    double best = -1e300;
                    glm::ivec3 ijk;
                    ijk[view.rightAxis] = ir;
                    ijk[view.downAxis] = id;
                    for (int k = 0; k < v.dims()[view.fwdAxis]; ++k) {
                        ijk[view.fwdAxis] = k;
                        best = std::max(best, v.value(ijk.x, ijk.y, ijk.z));
                    }
                    const double g = std::clamp((best - lo) / (hi - lo), 0.0, 1.0);
                    greys.push_back(int(std::lround(g * 255.0)));
                }
            if (greys.empty()) greys.push_back(0);  // background
            if (greys.size() > 1) ++e.ambiguous;
            e.grey.push_back(greys);
        }
    return e;
}

// "signed-random": int16 values over the whole range, -32768 included
// (headsq is stored signed but has no negative values); else a file or phantom.
Volume testVolume(const std::string& name) {
    if (name != "signed-random") return loadVolume(name);
    const glm::ivec3 d(23, 17, 29);
    std::vector<std::uint8_t> bytes(std::size_t(d.x) * d.y * d.z * 2);
    std::uint32_t state = 12345;
    for (std::size_t i = 0; i < bytes.size() / 2; ++i) {
        state = state * 1664525u + 1013904223u;  // a fixed LCG: reproducible
        std::int16_t v = std::int16_t(state >> 16);
        if (i % 97 == 0) v = -32768;
        std::memcpy(&bytes[i * 2], &v, 2);
    }
    return Volume(d, VoxelType::Int16, {0.8, 1.1, 1.0}, bytes, "signed-random");
}

class MipConventions : public GlTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(MipConventions, AxisMipEqualsCpuMaximumForEveryView) {
    const Volume v = testVolume(GetParam());
    for (const AxisView& view : kAxisViews) {
        SCOPED_TRACE(std::string("view ") + view.name);
        // One pixel per finer in-plane spacing, nearest, step 1.
        const Scene scene = axisViewScene(v, view, "mip");
        const Expected want = cpuMip(v, view, scene.width, scene.height);
        const std::vector<int> got = renderGrey(v, scene);
        int bad = 0, firstBad = -1;
        for (std::size_t i = 0; i < got.size(); ++i) {
            bool ok = false;
            for (int g : want.grey[i]) ok = ok || std::abs(got[i] - g) <= 1;
            if (!ok && bad++ == 0) firstBad = int(i);
        }
        EXPECT_EQ(bad, 0) << "first mismatch at pixel (" << firstBad % scene.width << ", "
                          << firstBad / scene.width << "): got " << (firstBad >= 0 ? got[firstBad] : 0)
                          << ", CPU maximum gives " << (firstBad >= 0 ? want.grey[firstBad][0] : 0);
        // Boundary pixels are rare; most pixels must have a single answer.
        EXPECT_LT(want.ambiguous, int(got.size()) / 20);
    }
}

INSTANTIATE_TEST_SUITE_P(RealAndPhantomVolumes, MipConventions,
                         ::testing::Values(datasetPath("tooth.nrrd"),      // non-cubic uint8
                                           datasetPath("silicium.nrrd"),   // 98x34x34: axis order
                                           datasetPath("cthead.nrrd"),     // uint16, spacing 1 1 2
                                           datasetPath("stent.nrrd"),      // uint16
                                           datasetPath("headsq.nrrd"),     // int16, 3.2 3.2 1.5
                                           std::string("phantom:shepp-logan:48"),   // float32
                                           std::string("signed-random")),           // int16 < 0
                         [](const auto& info) {
                             std::string s = info.param.substr(info.param.find_last_of("/:") + 1);
                             for (char& c : s)
                                 if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                             return s;
                         });

// A ray that misses the box shows the background; one through it does not.
TEST_F(GlTest, PixelsOutsideTheBoxShowTheBackground) {
    const Volume v = makePhantom("phantom:shells:32");
    Scene scene;
    scene.renderer = "mip";
    scene.camera.view = "+z";
    scene.camera.projection = Projection::Orthographic;
    scene.width = 64, scene.height = 32;  // the 32x32 box fills the middle half
    scene.background = glm::vec3(0.25f);
    scene.window = glm::dvec2(0.0, 255.0);
    const std::vector<int> g = renderGrey(v, scene);
    EXPECT_EQ(g[0], 64);                    // left margin: background 0.25 -> 64
    EXPECT_EQ(g[63], 64);                   // right margin
    EXPECT_EQ(g[16 * 64 + 32], 240 * 255 / 255);  // centre column passes through every shell: max 240
}

}  // namespace
}  // namespace voxlab::testing
