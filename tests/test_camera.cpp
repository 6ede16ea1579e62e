// Cameras: the axis-view table, the orbit's relation to it, a perspective
// render of the sphere phantom whose silhouette must have the analytic size
// from any direction, and the pan (its geometry, its scene key, and an
// orthographic render shifted by whole pixels).
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "support/error_of.h"
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

// Pinhole/parallel projection of a world point to continuous pixel
// coordinates, written from the conventions in camera.h (image offsets along
// right/down, per unit of depth in perspective), not from camera.cpp.
glm::dvec2 projectToPixel(const Camera& c, glm::dvec3 p) {
    const glm::dvec3 q = p - c.position;
    const double depth = c.projection == Projection::Perspective ? glm::dot(q, c.forward) : 1.0;
    return {0.5 * c.width + glm::dot(q, c.right) / (depth * c.pixelScale),
            0.5 * c.height + glm::dot(q, c.down) / (depth * c.pixelScale)};
}

// Pan is the look-at point's offset in bounding-sphere radii along right and
// down, so the box centre lands pan * radius / (world length of a pixel)
// pixels up and left of the image centre, from every direction, in both
// projections. Tolerance 1e-9 px: a few rounding errors of sums of O(100).
TEST(Camera, PanShiftsTheBoxCentreAgainstItInImageAxes) {
    const glm::dvec3 extent(40, 30, 20);
    const glm::dvec3 centre = 0.5 * extent;
    const double radius = 0.5 * glm::length(extent);
    const int w = 200, h = 150;
    for (Projection projection : {Projection::Orthographic, Projection::Perspective}) {
        for (const char* view : {"", "+x", "-y", "+z"}) {
            for (double az : {0.0, 75.0, -140.0}) {
                SCOPED_TRACE(std::string(projectionName(projection)) + " view '" + view + "' azimuth " +
                             std::to_string(az));
                CameraSpec spec;
                spec.projection = projection, spec.view = view, spec.azimuth = az, spec.zoom = 1.7;
                spec.pan = glm::dvec2(0.25, -0.4);
                const Camera c = Camera::make(spec, extent, w, h);
                // World length of a pixel at the box centre's depth.
                const double pixel = projection == Projection::Perspective
                                         ? c.pixelScale * spec.distance * radius
                                         : c.pixelScale;
                const glm::dvec2 at = projectToPixel(c, centre);
                EXPECT_NEAR(at.x, 0.5 * w - spec.pan.x * radius / pixel, 1e-9);
                EXPECT_NEAR(at.y, 0.5 * h - spec.pan.y * radius / pixel, 1e-9);
                // The pan moves the camera, never turns it.
                CameraSpec still = spec;
                still.pan = glm::dvec2(0.0);
                const Camera s = Camera::make(still, extent, w, h);
                expectNear(c.forward, s.forward);
                expectNear(c.right, s.right);
                EXPECT_EQ(c.pixelScale, s.pixelScale);
            }
        }
    }
}

// A zero pan must leave every camera bit-identical (renders depend on it).
TEST(Camera, ZeroPanIsTheCameraWithoutPan) {
    CameraSpec spec;
    spec.azimuth = 33.3, spec.elevation = -71.0;
    const Camera a = Camera::make(spec, {17, 9, 31}, 64, 48);
    spec.pan = glm::dvec2(1e-3, 0.0);
    const Camera b = Camera::make(spec, {17, 9, 31}, 64, 48);
    spec.pan = glm::dvec2(0.0);
    const Camera c = Camera::make(spec, {17, 9, 31}, 64, 48);
    EXPECT_NE(a.position, b.position);
    EXPECT_EQ(a.position, c.position);
}

TEST(Camera, PanInSceneJson) {
    using nlohmann::json;
    auto parse = [](const std::string& camera) {
        return Scene::fromJson(json::parse(R"({"dataset": "phantom:a", "camera": )" + camera + "}"), "scene.json",
                               "");
    };
    const Scene orbit = parse(R"({"azimuth": 10, "pan": [0.25, -1.5]})");
    EXPECT_EQ(orbit.camera.pan, glm::dvec2(0.25, -1.5));
    const Scene axis = parse(R"({"view": "+x", "zoom": 2, "pan": [1, 2]})");
    EXPECT_EQ(axis.camera.pan, glm::dvec2(1, 2));
    for (const Scene& s : {orbit, axis}) {
        const json out = s.toJson();
        const Scene back = Scene::fromJson(json::parse(out.dump()), "again.json", "");
        EXPECT_EQ(back.camera.pan, s.camera.pan) << out.dump();
        EXPECT_EQ(back.camera.view, s.camera.view);
    }
    // The default is left out, so files without a pan are written as before.
    EXPECT_FALSE(parse(R"({"azimuth": 10})").toJson()["camera"].contains("pan"));
    EXPECT_FALSE(parse(R"({"view": "-z"})").toJson()["camera"].contains("pan"));
    EXPECT_EQ(parse(R"({"azimuth": 10})").camera.pan, glm::dvec2(0.0));

    const std::pair<const char*, const char*> errors[] = {
        {R"({"pan": 1})", "scene.json: camera.pan: expected [x, y]"},
        {R"({"pan": [1, 2, 3]})", "scene.json: camera.pan: expected [x, y]"},
        {R"({"pan": [1, "2"]})", "scene.json: camera.pan[1]: expected a number"},
        {R"({"pan": [null, 2]})", "scene.json: camera.pan[0]: expected a number"},
    };
    for (const auto& [camera, message] : errors) {
        SCOPED_TRACE(camera);
        EXPECT_EQ(errorOf([&] { parse(camera); }), message);
    }
}

// End to end: an orthographic +z view whose pixels sit on voxel centres
// (one voxel per pixel), panned by a whole number of pixels, renders the same
// image shifted by that many pixels. Tolerance 1 grey level: the shifted
// sample positions agree only to rounding (pan is stored in radii).
TEST_F(GlTest, OrthographicPanShiftsTheRenderedImage) {
    const int n = 48, kx = 5, ky = -3;
    const Volume v = makePhantom("phantom:sphere:" + std::to_string(n));
    const double radius = 0.5 * std::sqrt(3.0) * n;
    Scene scene;
    scene.renderer = "mip";
    scene.camera.view = "+z";
    scene.camera.projection = Projection::Orthographic;
    scene.width = scene.height = n;
    scene.step = 0.25;
    scene.window = glm::dvec2(0.0, 1.0);
    const std::vector<int> still = renderGrey(v, scene);
    scene.camera.pan = glm::dvec2(kx, ky) / radius;  // look kx voxels right, ky down
    const std::vector<int> panned = renderGrey(v, scene);
    int compared = 0, lit = 0;
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            if (x + kx < 0 || x + kx >= n || y + ky < 0 || y + ky >= n) continue;
            const int expected = still[(y + ky) * n + x + kx];
            ASSERT_NEAR(panned[y * n + x], expected, 1) << "pixel " << x << "," << y;
            ++compared, lit += expected > 128;
        }
    }
    EXPECT_GT(compared, 1500);
    EXPECT_GT(lit, 500);  // the sphere is in the compared part
}

}  // namespace
}  // namespace voxlab::testing
