// Cameras: the axis-view table, the orbit's relation to it, and a
// perspective render of the sphere phantom whose silhouette must have the
// analytic size from any direction.
#include <gtest/gtest.h>

#include <cmath>

#include "support/gl_fixture.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/phantoms.h"

namespace voxlab::testing {
namespace {

void expectNear(glm::dvec3 a, glm::dvec3 b) {
    EXPECT_NEAR(a.x, b.x, 1e-9);
    EXPECT_NEAR(a.y, b.y, 1e-9);
    EXPECT_NEAR(a.z, b.z, 1e-9);
}

TEST(Camera, AxisViewsFollowTheReadmeTable) {
    struct Row { const char* view; glm::dvec3 fwd, right, down; };
    const Row rows[] = {{"+z", {0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {"-z", {0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
                        {"+x", {1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {"-x", {-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                        {"+y", {0, 1, 0}, {-1, 0, 0}, {0, 0, 1}},  {"-y", {0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
    for (const Row& r : rows) {
        SCOPED_TRACE(r.view);
        CameraSpec spec;
        spec.view = r.view;
        spec.projection = Projection::Orthographic;
        const Camera c = Camera::make(spec, {10, 20, 30}, 64, 64);
        expectNear(c.forward, r.fwd);
        expectNear(c.right, r.right);
        expectNear(c.down, r.down);
    }
}

TEST(Camera, OrbitAnglesReproduceAxisViews) {
    struct Row { double az, el; const char* view; };
    for (const Row& r : {Row{0, 0, "+z"}, Row{90, 0, "+x"}, Row{180, 0, "-z"}, Row{-90, 0, "-x"},
                         Row{0, -90, "-y"}, Row{180, 90, "+y"}}) {
        SCOPED_TRACE(r.view);
        CameraSpec orbit, axis;
        orbit.azimuth = r.az, orbit.elevation = r.el;
        axis.view = r.view;
        const Camera a = Camera::make(orbit, {8, 8, 8}, 32, 32), b = Camera::make(axis, {8, 8, 8}, 32, 32);
        expectNear(a.forward, b.forward);
        expectNear(a.right, b.right);
        expectNear(a.down, b.down);
        // The viewer continues a drag from these angles.
        double az = 1e9, el = 1e9;
        ASSERT_TRUE(axisViewOrbitAngles(r.view, &az, &el));
        EXPECT_EQ(az, r.az);
        EXPECT_EQ(el, r.el);
    }
    double az, el;
    EXPECT_FALSE(axisViewOrbitAngles("+w", &az, &el));
}

TEST(Camera, OrthographicAxisViewPutsPixelCentresOnVoxelCentres) {
    CameraSpec spec;
    spec.view = "+z";
    spec.projection = Projection::Orthographic;
    const Camera c = Camera::make(spec, {40, 30, 20}, 40, 30);
    glm::dvec3 o, d;
    c.ray(0.5, 0.5, &o, &d);
    EXPECT_NEAR(o.x, 0.5, 1e-12);
    EXPECT_NEAR(o.y, 0.5, 1e-12);
    c.ray(39.5, 29.5, &o, &d);
    EXPECT_NEAR(o.x, 39.5, 1e-12);
    EXPECT_NEAR(o.y, 29.5, 1e-12);
}

TEST(Camera, BadInputIsAnError) {
    CameraSpec spec;
    spec.view = "+w";
    EXPECT_THROW(Camera::make(spec, {1, 1, 1}, 8, 8), Error);
    EXPECT_THROW(parseProjection("fisheye"), Error);
    EXPECT_THROW(Camera::make(CameraSpec{}, {1, 1, 1}, 0, 8), Error);
}

// The sphere phantom's MIP is >= 0.5 exactly where a ray passes within R of
// the centre, so in perspective its silhouette is a disc of angular radius
// asin(R / D), whatever the direction: pixel radius tan(asin(R/D)) /
// tan(fov/2) * H/2. Checks the perspective ray set-up from several angles.
TEST_F(GlTest, PerspectiveSilhouetteOfTheSphereHasTheAnalyticSize) {
    const int n = 48;
    const Volume v = makePhantom("phantom:sphere:" + std::to_string(n));
    const double R = spherePhantomRadius(n);
    const double boundingRadius = 0.5 * std::sqrt(3.0) * n;
    for (auto [az, el] : {std::pair{0.0, 0.0}, {37.0, 21.0}, {-120.0, -60.0}, {200.0, 80.0}}) {
        SCOPED_TRACE("azimuth " + std::to_string(az) + ", elevation " + std::to_string(el));
        Scene scene;
        scene.renderer = "mip";
        scene.camera.azimuth = az, scene.camera.elevation = el;
        scene.camera.distance = 3.0, scene.camera.fov = 30.0;
        scene.width = scene.height = 160;
        scene.step = 0.25;
        scene.window = glm::dvec2(0.0, 1.0);
        const std::vector<int> g = renderGrey(v, scene);
        double count = 0, cx = 0, cy = 0;
        for (int y = 0; y < 160; ++y)
            for (int x = 0; x < 160; ++x)
                if (g[y * 160 + x] >= 128) count += 1, cx += x + 0.5, cy += y + 0.5;
        const double D = 3.0 * boundingRadius;
        const double rPixels = std::tan(std::asin(R / D)) / std::tan(M_PI / 12.0) * 80.0;
        EXPECT_NEAR(std::sqrt(count / M_PI), rPixels, 0.5);
        EXPECT_NEAR(cx / count, 80.0, 0.3);
        EXPECT_NEAR(cy / count, 80.0, 0.3);
    }
}

}  // namespace
}  // namespace voxlab::testing
