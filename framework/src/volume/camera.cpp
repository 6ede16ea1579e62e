// voxlab: camera set-up. See camera.h and the README for the conventions.
#include "voxlab/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "voxlab/error.h"

namespace voxlab {

const char* projectionName(Projection p) {
    return p == Projection::Orthographic ? "orthographic" : "perspective";
}

Projection parseProjection(const std::string& name) {
    if (name == "orthographic" || name == "ortho") return Projection::Orthographic;
    if (name == "perspective" || name == "persp") return Projection::Perspective;
    throw Error("unknown projection '" + name + "' (expected orthographic or perspective)");
}

namespace {

struct AxisBasis {
    const char* name;
    glm::dvec3 forward, right, down;
    double azimuth, elevation;  // the orbit that reproduces this view
};

// The axis-view table from the README: rays travel along `forward`; the
// image's x axis grows along `right` and its y axis along `down`.
constexpr AxisBasis kAxisViews[] = {
    {"+z", {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 0, 0},
    {"-z", {0, 0, -1}, {-1, 0, 0}, {0, 1, 0}, 180, 0},
    {"+x", {1, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90, 0},
    {"-x", {-1, 0, 0}, {0, 0, 1}, {0, 1, 0}, -90, 0},
    {"+y", {0, 1, 0}, {-1, 0, 0}, {0, 0, 1}, 180, 90},
    {"-y", {0, -1, 0}, {1, 0, 0}, {0, 0, 1}, 0, -90},
};

const AxisBasis* findAxisView(const std::string& view) {
    for (const AxisBasis& b : kAxisViews)
        if (view == b.name) return &b;
    return nullptr;
}

double radians(double degrees) { return degrees * (M_PI / 180.0); }

}  // namespace

bool isAxisView(const std::string& view) { return findAxisView(view) != nullptr; }

bool axisViewOrbitAngles(const std::string& view, double* azimuth, double* elevation) {
    const AxisBasis* b = findAxisView(view);
    if (!b) return false;
    *azimuth = b->azimuth, *elevation = b->elevation;
    return true;
}

Camera Camera::make(const CameraSpec& spec, glm::dvec3 extent, int width, int height) {
    if (width <= 0 || height <= 0) throw Error("image size must be positive");
    Camera cam;
    cam.width = width;
    cam.height = height;
    cam.projection = spec.projection;
    const glm::dvec3 centre = 0.5 * extent;
    const double radius = 0.5 * glm::length(extent);
    const double zoom = spec.zoom > 0.0 ? spec.zoom : 1.0;

    if (!spec.view.empty()) {
        const AxisBasis* b = findAxisView(spec.view);
        if (!b) throw Error("unknown view '" + spec.view + "' (expected +x -x +y -y +z -z)");
        cam.forward = b->forward;
        cam.right = b->right;
        cam.down = b->down;
    } else {
        // Orbit: azimuth turns about the y axis, elevation tilts towards
        // looking down from -y. At (0,0) this is exactly the +z view.
        const double az = radians(spec.azimuth), el = radians(spec.elevation);
        cam.forward = glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
        const glm::dvec3 up(std::sin(az) * std::sin(el), -std::cos(el), std::cos(az) * std::sin(el));
        cam.right = glm::normalize(glm::cross(cam.forward, up));
        cam.down = glm::normalize(glm::cross(cam.forward, cam.right));
    }

    // The point looked at: the box centre moved by the pan, in the image
    // plane. Adding a zero pan leaves `target` bit-identical to `centre`.
    const glm::dvec3 target = centre + radius * (spec.pan.x * cam.right + spec.pan.y * cam.down);

    if (cam.projection == Projection::Orthographic) {
        // Fit the projected box (axis views) or the bounding sphere (orbits)
        // into the image with one uniform scale, centred.
        double w, h;
        if (!spec.view.empty()) {
            w = std::abs(glm::dot(extent, cam.right));
            h = std::abs(glm::dot(extent, cam.down));
        } else {
            w = h = 2.0 * radius;
        }
        cam.pixelScale = std::max(w / width, h / height) / zoom;
        cam.position = target - cam.forward * (radius * 2.0);
    } else {
        const double dist = (spec.distance > 0.0 ? spec.distance : 4.0) * radius;
        cam.position = target - cam.forward * dist;
        cam.pixelScale = std::tan(radians(spec.fov) * 0.5) / (0.5 * height) / zoom;
    }
    return cam;
}

void Camera::ray(double px, double py, glm::dvec3* origin, glm::dvec3* direction) const {
    const double u = (px - 0.5 * width) * pixelScale;
    const double v = (py - 0.5 * height) * pixelScale;
    if (projection == Projection::Orthographic) {
        *origin = position + u * right + v * down;
        *direction = forward;
    } else {
        *origin = position;
        *direction = glm::normalize(forward + u * right + v * down);
    }
}

bool clipRayToBox(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& lo, const glm::dvec3& hi,
                  double* t0, double* t1) {
    double enter = 0.0, leave = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0) {
            if (origin[a] < lo[a] || origin[a] > hi[a]) return false;  // parallel to this slab, outside it
            continue;
        }
        const double ta = (lo[a] - origin[a]) / dir[a], tb = (hi[a] - origin[a]) / dir[a];
        enter = std::max(enter, std::min(ta, tb));
        leave = std::min(leave, std::max(ta, tb));
    }
    *t0 = enter, *t1 = leave;
    return leave > enter;
}

glm::mat4 Camera::clipFromWorld() const {
    // Image offsets from the centre: u = dot(q, right), v = dot(q, down) for
    // q = p - position, per unit of depth d = dot(q, forward) in
    // perspective. NDC x = u / (pixelScale W/2); NDC y points up, image rows
    // down: y = -v / (pixelScale H/2).
    const double sx = 1.0 / (pixelScale * 0.5 * width), sy = -1.0 / (pixelScale * 0.5 * height);
    glm::dmat4 m(0.0);  // column-major: m[column][row]
    const glm::dvec3 rows[2] = {right * sx, down * sy};
    for (int r = 0; r < 2; ++r) {
        for (int c = 0; c < 3; ++c) m[c][r] = rows[r][c];
        m[3][r] = -glm::dot(rows[r], position);
    }
    if (projection == Projection::Perspective) {
        for (int c = 0; c < 3; ++c) m[c][3] = forward[c];
        m[3][3] = -glm::dot(forward, position);
    } else {
        m[3][3] = 1.0;
    }
    return glm::mat4(m);
}

// Keeps the part of [*t0, *t1] where dot(p - point, normal) >= 0.
bool clipToHalfSpace(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& point,
                     const glm::dvec3& normal, double* t0, double* t1) {
    const double along = glm::dot(dir, normal), start = glm::dot(origin - point, normal);
    if (std::abs(along) < 1e-12) return start >= 0.0 && *t1 > *t0;
    const double t = -start / along;  // where the ray crosses the plane
    if (along > 0.0) *t0 = std::max(*t0, t);
    else *t1 = std::min(*t1, t);
    return *t1 > *t0;
}

}  // namespace voxlab
