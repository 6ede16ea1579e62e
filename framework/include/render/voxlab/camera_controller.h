// voxlab: the viewer's camera controller. Mouse drags, wheel steps and keys
// become changes of a CameraSpec; pure functions with no window or GUI, so
// that the feel of the viewer can be unit tested.
//
//  - Orbit: a horizontal drag turns the view about the vertical axis
//    (azimuth), a vertical drag tilts it (elevation). A drag across the
//    viewport's full height turns it by 180 degrees, whatever the window's
//    size in pixels. Elevation is not clamped at the poles: the view goes
//    over the top and comes out upside down, continuously. Upside down, a
//    horizontal drag turns azimuth the other way, so that the surface under
//    the mouse still moves with the mouse.
//  - Pan: the point under the mouse follows the mouse, exactly for the
//    orthographic projection and at the depth of the box centre for the
//    perspective one (CameraSpec::pan, camera.h).
//  - Zoom: each wheel step multiplies the zoom by 1.1, within [0.05, 50].
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "voxlab/camera.h"

namespace voxlab {

constexpr double kOrbitDegreesPerViewportHeight = 180.0;
constexpr double kZoomPerWheelStep = 1.1;
constexpr double kMinZoom = 0.05;
constexpr double kMaxZoom = 50.0;

// Turns the orbit by the given angles (degrees), leaving an axis view for the
// orbit angles that reproduce it first (axisViewOrbitAngles). Angles are kept
// in (-180, 180]. This is the script's "rotate AZ EL"; drags use orbitCamera.
void rotateCamera(CameraSpec* camera, double azimuthDegrees, double elevationDegrees);

// Orbits for a drag of (dx, dy) pixels in a viewport `viewportHeight` pixels
// tall (see the top of this file). From an orthographic axis view the image
// scale may change at the first drag, because axis views fit the box and
// orbits fit its bounding sphere; the overload below keeps it.
void orbitCamera(CameraSpec* camera, double dx, double dy, int viewportHeight);

// As above, but an axis view is first turned into the orbit that gives the
// same image (leaveAxisView), so the first drag has no jump.
void orbitCamera(CameraSpec* camera, glm::dvec3 extent, double dx, double dy, int viewportWidth,
                 int viewportHeight);

// Replaces an axis view by orbit angles, and for the orthographic projection
// rescales the zoom so that the image keeps its scale. Does nothing to an orbit.
void leaveAxisView(CameraSpec* camera, glm::dvec3 extent, int viewportWidth, int viewportHeight);

// Pans for a drag of (dx, dy) pixels, so that what was under pixel (x, y) is
// under (x + dx, y + dy) afterwards (see the top of this file). `extent` is
// the volume's box, as given to Camera::make.
void panCamera(CameraSpec* camera, glm::dvec3 extent, double dx, double dy, int viewportWidth,
               int viewportHeight);

// Zooms by wheel steps: zoom *= 1.1^steps, clamped to [kMinZoom, kMaxZoom].
void zoomCamera(CameraSpec* camera, double steps);

// The default view (CameraSpec's defaults: an orbit, no pan, zoom 1); the
// projection is kept.
void resetCamera(CameraSpec* camera);

// Looks along an axis ("+x" ... "-z"), the whole box in view: pan and zoom
// are reset, the projection is kept. Throws voxlab::Error for another name.
void setAxisView(CameraSpec* camera, const std::string& view);

// Perspective <-> orthographic.
void toggleProjection(CameraSpec* camera);

}  // namespace voxlab
