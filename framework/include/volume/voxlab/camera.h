// voxlab: cameras and the rays they shoot.
//
// Conventions (the README has the full table):
//  - Axis views "+x -x +y -y +z -z" name the direction in which rays travel.
//  - Image pixel (px, py), py growing downwards, has its centre at
//    (px + 1/2, py + 1/2).
//  - An orthographic axis view scales the box's projected rectangle
//    uniformly to fit the image, centred. When the image size equals the
//    projected dimensions in voxels (and the spacing is the same along both
//    image axes), pixel centres fall exactly on voxel centres.
//  - The orbit camera looks at the box centre from azimuth/elevation
//    (degrees) at a distance given in units of the box's bounding-sphere
//    radius. Azimuth 0, elevation 0 is the +z view; azimuth 90 is +x;
//    positive elevation looks down from above (from -y, the image "up" of the
//    horizontal views).
//  - Pan moves the point looked at (the image centre) away from the box
//    centre, along the image's own right and down directions, in units of
//    the bounding-sphere radius: pan (0.5, 0) looks at a point half a radius
//    to the right of the centre, so the volume appears shifted left. Being
//    tied to the image axes, a pan stays a shift of the image when the view
//    turns. Both projections and the axis views honour it; the camera is
//    translated parallel to the image plane, its direction is unchanged.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace voxlab {

enum class Projection { Orthographic, Perspective };

const char* projectionName(Projection p);
Projection parseProjection(const std::string& name);  // throws voxlab::Error

struct CameraSpec {
    // Either an axis view ("+x", ..., "-z") or an orbit (when view is empty).
    std::string view;
    double azimuth = 30.0;    // degrees
    double elevation = 20.0;  // degrees
    double distance = 4.0;    // in bounding-sphere radii (perspective; 4 fits the box at fov 30)
    double fov = 30.0;        // vertical field of view, degrees (perspective)
    double zoom = 1.0;        // >1 magnifies
    glm::dvec2 pan{0.0};      // look-at point minus box centre, in bounding-sphere radii along (right, down)
    Projection projection = Projection::Perspective;
};

bool isAxisView(const std::string& view);

// The orbit angles (degrees) that give the same camera as an axis view, so
// that an interaction starting from an axis view continues smoothly.
// Returns false for a name that is not an axis view.
bool axisViewOrbitAngles(const std::string& view, double* azimuth, double* elevation);

// The camera as the renderers use it: a ray for every pixel.
struct Camera {
    glm::dvec3 position{0.0};  // eye (perspective) or centre of the image plane (ortho)
    glm::dvec3 forward{0.0, 0.0, 1.0};
    glm::dvec3 right{1.0, 0.0, 0.0};
    glm::dvec3 down{0.0, 1.0, 0.0};
    Projection projection = Projection::Orthographic;
    // Orthographic: world units per pixel. Perspective: tan(fov/2) / (height/2).
    double pixelScale = 1.0;
    int width = 1;
    int height = 1;

    // Builds the camera for a box [0, extent] and an image of width x height.
    static Camera make(const CameraSpec& spec, glm::dvec3 extent, int width, int height);

    // Ray through the centre of pixel (px, py) (continuous pixel coordinates,
    // so pass px + 0.5 for a pixel centre). Direction is unit length.
    void ray(double px, double py, glm::dvec3* origin, glm::dvec3* direction) const;

    // The matrix from world to clip space that draws geometry where these
    // rays see it (object-order renderers): a world point on the ray through
    // pixel (px, py) lands on that pixel. Clip z is 0 (no depth test);
    // perspective clip w is the depth along `forward`, so geometry behind
    // the eye is clipped away.
    glm::mat4 clipFromWorld() const;
};

// Clips the ray origin + t dir to the box [lo, hi] (the slab method): *t0
// and *t1 receive where it enters and leaves, with t0 never behind the
// origin. Returns whether any of the ray is inside.
bool clipRayToBox(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& lo, const glm::dvec3& hi,
                  double* t0, double* t1);

// Keeps the part of [*t0, *t1] where dot(p - point, normal) >= 0 (a ray
// parallel to the plane is kept whole or not at all). Returns whether any
// of the ray is left.
bool clipToHalfSpace(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& point,
                     const glm::dvec3& normal, double* t0, double* t1);

}  // namespace voxlab
