// voxlab: the viewer's camera controller. See camera_controller.h.
#include "voxlab/camera_controller.h"

#include <algorithm>
#include <cmath>

#include "voxlab/error.h"

namespace voxlab {

namespace {

// An axis view becomes the orbit with the same direction and image axes
// (the camera table guarantees that right and down agree, so a pan carries
// over unchanged).
void axisViewToOrbitAngles(CameraSpec* camera) {
    if (camera->view.empty()) return;
    if (!axisViewOrbitAngles(camera->view, &camera->azimuth, &camera->elevation))
        throw Error("unknown view '" + camera->view + "' (expected +x -x +y -y +z -z)");
    camera->view.clear();
}

}  // namespace

void rotateCamera(CameraSpec* camera, double azimuthDegrees, double elevationDegrees) {
    axisViewToOrbitAngles(camera);
    // Camera::make builds the view from sines and cosines, so wrapping the
    // angles by whole turns changes nothing but keeps saved scenes readable.
    // Elevations past +-90 are legal: the view is then upside down.
    camera->azimuth = std::remainder(camera->azimuth + azimuthDegrees, 360.0);
    camera->elevation = std::remainder(camera->elevation + elevationDegrees, 360.0);
}

void orbitCamera(CameraSpec* camera, double dx, double dy, int viewportHeight) {
    axisViewToOrbitAngles(camera);
    const double degreesPerPixel = kOrbitDegreesPerViewportHeight / std::max(viewportHeight, 1);
    // Azimuth turns the camera about the world's y axis. Upright (|elevation|
    // < 90), y points down the image and a drag to the right moves the
    // volume's front to the right; upside down, y points up the image and
    // the same turn would move it left, so the sign follows cos(elevation).
    const double upright = std::cos(camera->elevation * (M_PI / 180.0)) >= 0.0 ? 1.0 : -1.0;
    rotateCamera(camera, upright * degreesPerPixel * dx, degreesPerPixel * dy);
}

void orbitCamera(CameraSpec* camera, glm::dvec3 extent, double dx, double dy, int viewportWidth,
                 int viewportHeight) {
    leaveAxisView(camera, extent, viewportWidth, viewportHeight);
    orbitCamera(camera, dx, dy, viewportHeight);
}

void leaveAxisView(CameraSpec* camera, glm::dvec3 extent, int viewportWidth, int viewportHeight) {
    if (camera->view.empty()) return;
    const Camera before = Camera::make(*camera, extent, viewportWidth, viewportHeight);
    axisViewToOrbitAngles(camera);
    if (camera->projection == Projection::Orthographic) {
        // pixelScale is (fit / zoom); the orbit's fit (the bounding sphere) is
        // at least the axis view's (the projected box), so scaling the zoom
        // by their ratio gives the orbit the axis view's pixelScale.
        const Camera after = Camera::make(*camera, extent, viewportWidth, viewportHeight);
        camera->zoom *= after.pixelScale / before.pixelScale;
    }
}

void panCamera(CameraSpec* camera, glm::dvec3 extent, double dx, double dy, int viewportWidth,
               int viewportHeight) {
    const double radius = 0.5 * glm::length(extent);
    if (!(radius > 0.0)) return;
    const Camera cam = Camera::make(*camera, extent, viewportWidth, viewportHeight);
    // World length of one pixel where the drag is followed: the image plane
    // (orthographic), or the plane through the box centre parallel to it
    // (perspective: pixelScale is per unit of depth). The pan keeps the
    // camera's distance to that plane, so the relation is linear and exact.
    double worldPerPixel = cam.pixelScale;
    if (cam.projection == Projection::Perspective)
        worldPerPixel *= glm::dot(0.5 * extent - cam.position, cam.forward);
    // Content moves with the mouse when the look-at point moves against it.
    camera->pan -= glm::dvec2(dx, dy) * (worldPerPixel / radius);
}

void zoomCamera(CameraSpec* camera, double steps) {
    const double zoom = camera->zoom > 0.0 ? camera->zoom : 1.0;
    camera->zoom = std::clamp(zoom * std::pow(kZoomPerWheelStep, steps), kMinZoom, kMaxZoom);
}

void resetCamera(CameraSpec* camera) {
    const Projection projection = camera->projection;
    *camera = CameraSpec{};
    camera->projection = projection;
}

void setAxisView(CameraSpec* camera, const std::string& view) {
    if (!isAxisView(view)) throw Error("unknown view '" + view + "' (expected +x -x +y -y +z -z)");
    camera->view = view;
    camera->pan = glm::dvec2(0.0);
    camera->zoom = 1.0;
}

void toggleProjection(CameraSpec* camera) {
    camera->projection =
        camera->projection == Projection::Orthographic ? Projection::Perspective : Projection::Orthographic;
}

}  // namespace voxlab
