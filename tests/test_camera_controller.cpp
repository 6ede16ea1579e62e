// The viewer's camera controller: pans that keep the point under the mouse
// under the mouse, orbits that are continuous over the poles and move the
// volume with the mouse, zoom limits, reset and axis views. Pure CPU tests:
// the oracles are Camera::make's rays and a projection written from the
// conventions in camera.h.
#include <gtest/gtest.h>

#include <cmath>

#include "support/error_of.h"
#include "voxlab/camera.h"
#include "voxlab/camera_controller.h"
#include "voxlab/error.h"

namespace voxlab::testing {
namespace {

const glm::dvec3 kExtent(40, 30, 20);
const glm::dvec3 kCentre = 0.5 * kExtent;
constexpr int kWidth = 320, kHeight = 200;

// Continuous pixel coordinates of a world point: offsets along right/down
// from the image centre, per unit of depth in perspective (camera.h).
glm::dvec2 projectToPixel(const Camera& c, glm::dvec3 p) {
    const glm::dvec3 q = p - c.position;
    const double depth = c.projection == Projection::Perspective ? glm::dot(q, c.forward) : 1.0;
    return {0.5 * c.width + glm::dot(q, c.right) / (depth * c.pixelScale),
            0.5 * c.height + glm::dot(q, c.down) / (depth * c.pixelScale)};
}

// Distance from point p to the ray through pixel (px, py).
double distanceToRay(const Camera& c, double px, double py, glm::dvec3 p) {
    glm::dvec3 origin, direction;
    c.ray(px, py, &origin, &direction);
    const glm::dvec3 q = p - origin;
    return glm::length(q - glm::dot(q, direction) * direction);
}

double angleBetween(glm::dvec3 a, glm::dvec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0));
}

Camera make(const CameraSpec& spec) { return Camera::make(spec, kExtent, kWidth, kHeight); }

std::vector<CameraSpec> someCameras(Projection projection) {
    std::vector<CameraSpec> specs;
    for (const char* view : {"", "+x", "-z", "+y"}) {
        CameraSpec s;
        s.projection = projection, s.view = view, s.azimuth = -57.0, s.elevation = 33.0, s.zoom = 2.3;
        s.pan = glm::dvec2(-0.2, 0.15);
        specs.push_back(s);
    }
    CameraSpec upsideDown;
    upsideDown.projection = projection, upsideDown.azimuth = 120.0, upsideDown.elevation = 150.0;
    specs.push_back(upsideDown);
    return specs;
}

std::string describe(const CameraSpec& s) {
    return std::string(projectionName(s.projection)) + " view '" + s.view + "' az " + std::to_string(s.azimuth) +
           " el " + std::to_string(s.elevation);
}

// --- pan ---------------------------------------------------------------------

// Orthographic: the world point seen through pixel (x, y) is seen through
// (x + dx, y + dy) after the pan. Tolerance 1e-9 world units on distances of
// O(100): rounding only.
TEST(CameraController, OrthographicPanKeepsThePointUnderTheMouse) {
    for (CameraSpec spec : someCameras(Projection::Orthographic)) {
        SCOPED_TRACE(describe(spec));
        const double x = 61.25, y = 143.5, dx = 13.5, dy = -27.75;
        const Camera before = make(spec);
        glm::dvec3 origin, direction;
        before.ray(x, y, &origin, &direction);
        const glm::dvec3 seen = origin + 37.0 * direction;  // any point along the ray
        panCamera(&spec, kExtent, dx, dy, kWidth, kHeight);
        const Camera after = make(spec);
        EXPECT_LT(distanceToRay(after, x + dx, y + dy, seen), 1e-9);
        // ... and not through the old pixel (the test can tell a pan that did nothing).
        EXPECT_GT(distanceToRay(after, x, y, seen), 1.0);
    }
}

// Perspective: the box centre's image moves by exactly the drag. Tolerance
// 1e-9 px: rounding only.
TEST(CameraController, PerspectivePanMovesTheBoxCentreWithTheMouse) {
    for (CameraSpec spec : someCameras(Projection::Perspective)) {
        SCOPED_TRACE(describe(spec));
        const double dx = -41.0, dy = 18.5;
        const glm::dvec2 before = projectToPixel(make(spec), kCentre);
        panCamera(&spec, kExtent, dx, dy, kWidth, kHeight);
        const glm::dvec2 after = projectToPixel(make(spec), kCentre);
        EXPECT_NEAR(after.x - before.x, dx, 1e-9);
        EXPECT_NEAR(after.y - before.y, dy, 1e-9);
        // The box centre stays on the ray through its new pixel.
        EXPECT_LT(distanceToRay(make(spec), after.x, after.y, kCentre), 1e-9);
    }
}

TEST(CameraController, PanDoesNotTurnOrZoom) {
    CameraSpec spec;
    const Camera a = make(spec);
    panCamera(&spec, kExtent, 30, 40, kWidth, kHeight);
    const Camera b = make(spec);
    EXPECT_EQ(a.forward, b.forward);
    EXPECT_EQ(a.pixelScale, b.pixelScale);
    EXPECT_NE(a.position, b.position);
    EXPECT_EQ(spec.azimuth, CameraSpec().azimuth);
    EXPECT_EQ(spec.zoom, 1.0);
}

// --- orbit -------------------------------------------------------------------

TEST(CameraController, ZeroDragChangesNothing) {
    CameraSpec orbit;
    orbit.azimuth = 12.0, orbit.elevation = -34.0, orbit.pan = glm::dvec2(0.1, 0.2);
    CameraSpec moved = orbit;
    orbitCamera(&moved, 0.0, 0.0, kHeight);
    EXPECT_EQ(moved.azimuth, orbit.azimuth);
    EXPECT_EQ(moved.elevation, orbit.elevation);
    EXPECT_EQ(moved.pan, orbit.pan);
    EXPECT_EQ(moved.zoom, orbit.zoom);

    // From an axis view, a zero drag leaves the same camera, even its
    // orthographic scale (the overload that knows the box).
    for (const char* view : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
        SCOPED_TRACE(view);
        CameraSpec axis;
        axis.view = view, axis.projection = Projection::Orthographic, axis.zoom = 1.5;
        axis.pan = glm::dvec2(0.3, -0.1);
        const Camera a = make(axis);
        orbitCamera(&axis, kExtent, 0.0, 0.0, kWidth, kHeight);
        EXPECT_EQ(axis.view, "");
        const Camera b = make(axis);
        EXPECT_LT(glm::length(a.forward - b.forward), 1e-12);
        EXPECT_LT(glm::length(a.right - b.right), 1e-12);
        EXPECT_LT(glm::length(a.down - b.down), 1e-12);
        EXPECT_NEAR(b.pixelScale / a.pixelScale, 1.0, 1e-12);
        EXPECT_LT(glm::length(a.position - b.position), 1e-9);
    }
}

TEST(CameraController, HorizontalDragKeepsElevation) {
    for (double elevation : {-60.0, 0.0, 20.0, 135.0}) {
        CameraSpec spec;
        spec.elevation = elevation;
        orbitCamera(&spec, 57.0, 0.0, kHeight);
        EXPECT_EQ(spec.elevation, elevation);
        EXPECT_NE(spec.azimuth, CameraSpec().azimuth);
    }
}

// A drag across the viewport's height turns the view by half a turn, at any
// window size: from the +z direction, forward is reversed.
TEST(CameraController, FullHeightDragIsHalfATurn) {
    for (int height : {200, 1000}) {
        CameraSpec spec;
        spec.azimuth = 0.0, spec.elevation = 0.0;
        orbitCamera(&spec, height, 0.0, height);
        EXPECT_LT(glm::length(make(spec).forward - glm::dvec3(0, 0, -1)), 1e-12);
        spec.azimuth = 0.0;
        orbitCamera(&spec, 0.0, height / 2.0, height);  // a quarter turn looks straight down
        EXPECT_LT(glm::length(make(spec).forward - glm::dvec3(0, 1, 0)), 1e-12);
    }
}

// Grab-and-drag feel: the point of the volume nearest the viewer (in front
// of the box centre) moves the way the mouse does, also upside down (past a
// pole), where the azimuth has to turn the other way.
TEST(CameraController, DragMovesTheFrontOfTheVolumeWithTheMouse) {
    const double radius = 0.5 * glm::length(kExtent);
    for (double elevation : {-150.0, -30.0, 0.0, 45.0, 100.0, 170.0}) {
        for (glm::dvec2 drag : {glm::dvec2(6, 0), glm::dvec2(-6, 0), glm::dvec2(0, 6), glm::dvec2(0, -6)}) {
            SCOPED_TRACE("elevation " + std::to_string(elevation) + " drag " + std::to_string(drag.x) + "," +
                         std::to_string(drag.y));
            CameraSpec spec;
            spec.azimuth = 25.0, spec.elevation = elevation;
            const Camera before = make(spec);
            const glm::dvec3 front = kCentre - radius * before.forward;
            const glm::dvec2 p0 = projectToPixel(before, front);
            orbitCamera(&spec, drag.x, drag.y, kHeight);
            const glm::dvec2 moved = projectToPixel(make(spec), front) - p0;
            // Same direction as the drag, and mostly along it.
            EXPECT_GT(glm::dot(moved, drag), 0.9 * glm::length(moved) * glm::length(drag));
        }
    }
}

// Crossing a pole by dragging vertically: the view keeps turning (no clamp)
// and every camera axis moves by at most the drag's angle per step.
TEST(CameraController, CrossingAPoleIsContinuous) {
    for (double start : {80.0, -80.0}) {
        SCOPED_TRACE("from elevation " + std::to_string(start));
        CameraSpec spec;
        spec.azimuth = 40.0, spec.elevation = start;
        const double sign = start > 0 ? 1.0 : -1.0;
        const double degreesPerStep = 180.0 / kHeight * 1.0;
        Camera previous = make(spec);
        const glm::dvec3 firstForward = previous.forward;
        for (int i = 0; i < 40; ++i) {  // 36 degrees: from 80 to 116 (or -80 to -116)
            orbitCamera(&spec, 0.0, sign * 1.0, kHeight);
            const Camera next = make(spec);
            // Tolerance: the step's angle plus rounding.
            const double limit = degreesPerStep * M_PI / 180.0 + 1e-9;
            EXPECT_LE(angleBetween(previous.forward, next.forward), limit) << "step " << i;
            EXPECT_LE(angleBetween(previous.right, next.right), limit) << "step " << i;
            EXPECT_LE(angleBetween(previous.down, next.down), limit) << "step " << i;
            previous = next;
        }
        // Over the pole: the horizontal part of forward now points the other way.
        const glm::dvec2 h0(firstForward.x, firstForward.z), h1(previous.forward.x, previous.forward.z);
        EXPECT_LT(glm::dot(h0, h1), 0.0);
        EXPECT_NEAR(std::abs(spec.elevation), 116.0, 1e-9);
    }
}

// The first small drag from an axis view gives a camera close to that view:
// each axis turns by at most the drag's angle (a (1.5, -1.5) px drag at 0.9
// deg/px: 1.35 degrees of azimuth and of elevation, together < 2 degrees).
TEST(CameraController, FirstDragFromAnAxisViewStaysNearIt) {
    for (Projection projection : {Projection::Orthographic, Projection::Perspective}) {
        for (const char* view : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
            SCOPED_TRACE(std::string(view) + " " + projectionName(projection));
            CameraSpec spec;
            spec.view = view, spec.projection = projection;
            const Camera axis = make(spec);
            CameraSpec quick = spec;  // the overload without the box
            orbitCamera(&spec, kExtent, 1.5, -1.5, kWidth, kHeight);
            orbitCamera(&quick, 1.5, -1.5, kHeight);
            const double limit = 2.0 * M_PI / 180.0;
            for (const CameraSpec& s : {spec, quick}) {
                EXPECT_TRUE(s.view.empty());
                const Camera c = make(s);
                EXPECT_LT(angleBetween(axis.forward, c.forward), limit);
                EXPECT_LT(angleBetween(axis.right, c.right), limit);
                EXPECT_LT(angleBetween(axis.down, c.down), limit);
                EXPECT_GT(angleBetween(axis.forward, c.forward), 0.0);
            }
            // The overload with the box also keeps the image scale.
            EXPECT_NEAR(make(spec).pixelScale / axis.pixelScale, 1.0, 1e-12);
        }
    }
}

TEST(CameraController, RotateTurnsByDegreesAndWraps) {
    CameraSpec spec;
    spec.azimuth = 170.0, spec.elevation = 10.0;
    rotateCamera(&spec, 30.0, -25.0);
    EXPECT_NEAR(spec.azimuth, -160.0, 1e-12);
    EXPECT_NEAR(spec.elevation, -15.0, 1e-12);
    spec.view = "+x";
    rotateCamera(&spec, 10.0, 5.0);
    EXPECT_EQ(spec.view, "");
    EXPECT_NEAR(spec.azimuth, 100.0, 1e-12);
    EXPECT_NEAR(spec.elevation, 5.0, 1e-12);
}

// --- zoom, reset, views ----------------------------------------------------------

TEST(CameraController, ZoomStepsAndClamps) {
    CameraSpec spec;
    zoomCamera(&spec, 1.0);
    EXPECT_NEAR(spec.zoom, 1.1, 1e-15);
    zoomCamera(&spec, -2.0);
    EXPECT_NEAR(spec.zoom, 1.0 / 1.1, 1e-15);
    zoomCamera(&spec, 1000.0);
    EXPECT_EQ(spec.zoom, 50.0);
    zoomCamera(&spec, -1.0);
    EXPECT_NEAR(spec.zoom, 50.0 / 1.1, 1e-12);
    zoomCamera(&spec, -1000.0);
    EXPECT_EQ(spec.zoom, 0.05);
    spec.zoom = 0.0;  // an invalid zoom restarts from 1
    zoomCamera(&spec, 0.0);
    EXPECT_EQ(spec.zoom, 1.0);
}

TEST(CameraController, ResetAxisViewsAndProjection) {
    CameraSpec spec;
    spec.projection = Projection::Orthographic;
    spec.azimuth = 1, spec.elevation = 2, spec.distance = 9, spec.fov = 50, spec.zoom = 3;
    spec.pan = glm::dvec2(1, 1), spec.view = "+x";
    resetCamera(&spec);
    const CameraSpec defaults;
    EXPECT_EQ(spec.view, defaults.view);
    EXPECT_EQ(spec.azimuth, defaults.azimuth);
    EXPECT_EQ(spec.elevation, defaults.elevation);
    EXPECT_EQ(spec.distance, defaults.distance);
    EXPECT_EQ(spec.fov, defaults.fov);
    EXPECT_EQ(spec.zoom, defaults.zoom);
    EXPECT_EQ(spec.pan, defaults.pan);
    EXPECT_EQ(spec.projection, Projection::Orthographic);  // kept

    spec.zoom = 4, spec.pan = glm::dvec2(0.5, 0);
    setAxisView(&spec, "-y");
    EXPECT_EQ(spec.view, "-y");
    EXPECT_EQ(spec.zoom, 1.0);
    EXPECT_EQ(spec.pan, glm::dvec2(0.0));
    EXPECT_EQ(errorOf([&] { setAxisView(&spec, "up"); }), "unknown view 'up' (expected +x -x +y -y +z -z)");
    EXPECT_EQ(spec.view, "-y");

    toggleProjection(&spec);
    EXPECT_EQ(spec.projection, Projection::Perspective);
    toggleProjection(&spec);
    EXPECT_EQ(spec.projection, Projection::Orthographic);
}

}  // namespace
}  // namespace voxlab::testing
