// The isosurface renderer "iso", checked against analytic geometry. On the
// sphere phantom the 0.5 isosurface is exactly the sphere of radius
// R = 0.35 N around the box centre c (phantoms.h), so every ray's first hit
// has a closed form: with b = dot(c - o, d) and the closest approach
// q = |c - o - b d|, a ray with q < R meets the sphere first at
//     t = b - sqrt(R^2 - q^2).
// With depth=1 the renderer shows that distance as grey (README):
//     grey = 1 - (t - t_near) / (2 rho),  t_near = dot(c - o, d) - rho,
// rho = |extent| / 2, which this file turns back into t. The float image is
// read unrounded, so t comes back to about 1e-5 voxel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "support/gl_fixture.h"
#include "voxlab/phantoms.h"

namespace voxlab::testing {
namespace {

constexpr int kN = 48;  // phantom edge: R = 16.8 voxels, the surface ramp 4 voxels wide

// One pixel's ray and its analytic meeting with the sphere.
struct SphereRay {
    glm::dvec3 origin, direction;
    double closest = 0.0;  // distance of the ray's closest approach to the centre
    double tHit = 0.0;     // first intersection with the sphere, when closest < R
};

SphereRay sphereRay(const Camera& cam, int px, int py, glm::dvec3 centre, double radius) {
    SphereRay r;
    cam.ray(px + 0.5, py + 0.5, &r.origin, &r.direction);
    const glm::dvec3 oc = centre - r.origin;
    const double b = glm::dot(oc, r.direction);
    r.closest = glm::length(oc - b * r.direction);
    if (r.closest < radius) r.tHit = b - std::sqrt(radius * radius - r.closest * r.closest);
    return r;
}

// The README's depth grey turned back into a distance along the ray.
double depthToDistance(double grey, const SphereRay& r, glm::dvec3 extent) {
    const glm::dvec3 c = 0.5 * extent;
    const double rho = 0.5 * glm::length(extent);
    const double tNear = glm::dot(c - r.origin, r.direction) - rho;
    return tNear + (1.0 - grey) * 2.0 * rho;
}

CameraSpec axisCamera(const char* view) {
    CameraSpec c;
    c.view = view;
    c.projection = Projection::Orthographic;
    return c;
}

CameraSpec orbitCamera(double azimuth, double elevation) {
    CameraSpec c;
    c.azimuth = azimuth;
    c.elevation = elevation;
    c.projection = Projection::Orthographic;
    return c;
}

Scene isoScene(const CameraSpec& camera, int size, double step, int refinementSteps, double isovalue = 0.5) {
    Scene scene;
    scene.renderer = "iso";
    scene.camera = camera;
    scene.width = scene.height = size;
    scene.step = step;
    scene.interpolation = Interpolation::Trilinear;
    scene.parameters["isovalue"] = isovalue;
    scene.parameters["refinement_steps"] = refinementSteps;
    scene.parameters["depth"] = 1;
    return scene;
}

struct DepthError {
    double maxError = 0.0;  // over the core pixels, in voxels
    int checked = 0;        // core pixels compared
    int missed = 0;         // core pixels that showed no surface (background)
    std::string worst;
};

// Compares the rendered hit distance with the analytic one at every pixel
// whose ray passes the centre closer than `core` * R: away from the
// silhouette, where a grazing ray would turn a tiny radial error into a
// large error along the ray. Background is black, so a missed surface shows
// grey 0 and is counted separately.
DepthError depthError(const Volume& v, const Scene& scene, double radius, double core = 0.9) {
    GlTest::engine().setVolume(v);
    const Image img = GlTest::engine().render(scene);
    const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
    const glm::dvec3 centre = 0.5 * v.extent();
    DepthError e;
    for (int py = 0; py < scene.height; ++py)
        for (int px = 0; px < scene.width; ++px) {
            const SphereRay r = sphereRay(cam, px, py, centre, radius);
            if (r.closest >= core * radius) continue;
            ++e.checked;
            const double grey = img.at(px, py).r;
            if (grey <= 0.0) {
                ++e.missed;
                continue;
            }
            const double err = std::abs(depthToDistance(grey, r, v.extent()) - r.tHit);
            if (err > e.maxError) {
                e.maxError = err;
                char buf[160];
                std::snprintf(buf, sizeof buf, "pixel (%d, %d): t = %.4f, analytic %.4f", px, py,
                              depthToDistance(grey, r, v.extent()), r.tHit);
                e.worst = buf;
            }
        }
    return e;
}

// Tolerance for refined hits: 0.1 voxel. The 8 bisection steps of a step-1
// interval leave 1/512 voxel; the rest is the trilinear field's own 0.5
// surface, which bulges from the true sphere by about 3 h^2 / (8 R) (the
// curvature of r = |p - c| over one cell) = 0.02 voxel here, divided by the
// cosine of the incidence angle (>= 0.43 for rays inside 0.9 R).
constexpr double kRefinedTolerance = 0.1;

TEST_F(GlTest, IsoDepthMatchesTheAnalyticSphereInEveryAxisView) {
    const Volume v = makePhantom("phantom:sphere:" + std::to_string(kN));
    const double radius = spherePhantomRadius(kN);
    for (const char* view : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
        SCOPED_TRACE(std::string("view ") + view);
        const DepthError e = depthError(v, isoScene(axisCamera(view), kN, 1.0, 8), radius);
        std::printf("[ measured ] view %s: max |t - t_analytic| = %.4f voxel\n", view, e.maxError);
        EXPECT_GT(e.checked, 600);  // pi (0.9 R)^2 = 718 pixels
        EXPECT_EQ(e.missed, 0);
        EXPECT_LT(e.maxError, kRefinedTolerance) << e.worst;
    }
}

TEST_F(GlTest, IsoDepthMatchesTheAnalyticSphereInObliqueOrbits) {
    const Volume v = makePhantom("phantom:sphere:" + std::to_string(kN));
    const double radius = spherePhantomRadius(kN);
    for (auto [az, el] : {std::pair{30.0, 20.0}, std::pair{-125.0, -50.0}}) {
        SCOPED_TRACE("orbit " + std::to_string(az) + " " + std::to_string(el));
        // Orthographic orbits fit the bounding sphere (radius 0.87 N): 64
        // pixels give about 1.3 voxel per pixel.
        const DepthError e = depthError(v, isoScene(orbitCamera(az, el), 64, 1.0, 8), radius);
        std::printf("[ measured ] orbit %g/%g: max |t - t_analytic| = %.4f voxel\n", az, el, e.maxError);
        EXPECT_GT(e.checked, 350);
        EXPECT_EQ(e.missed, 0);
        EXPECT_LT(e.maxError, kRefinedTolerance) << e.worst;
    }
}

// The isovalue is in data units: a uint16 sphere with values 1000 + 2000 f
// (f the phantom's formula) has its 2000 isosurface on the same sphere.
// Rounding to integers moves it by at most 0.5 / 2000 of the ramp's 4
// voxels: 0.001 voxel.
TEST_F(GlTest, IsovalueIsInDataUnits) {
    const glm::ivec3 dims(kN);
    std::vector<std::uint8_t> bytes(std::size_t(kN) * kN * kN * 2);
    for (int k = 0; k < kN; ++k)
        for (int j = 0; j < kN; ++j)
            for (int i = 0; i < kN; ++i) {
                const double f = spherePhantomValue(kN, glm::dvec3(i + 0.5, j + 0.5, k + 0.5));
                const std::uint16_t u = std::uint16_t(std::lround(1000.0 + 2000.0 * f));
                std::memcpy(&bytes[((std::size_t(k) * kN + j) * kN + i) * 2], &u, 2);
            }
    const Volume v(dims, VoxelType::UInt16, glm::dvec3(1.0), bytes, "sphere16");
    const DepthError e = depthError(v, isoScene(axisCamera("+x"), kN, 1.0, 8, 2000.0), spherePhantomRadius(kN));
    EXPECT_GT(e.checked, 600);
    EXPECT_EQ(e.missed, 0);
    EXPECT_LT(e.maxError, kRefinedTolerance) << e.worst;
}

// Without refinement the hit is the first sample past the crossing, up to a
// whole step late; 8 bisection steps cut that to step / 256 (plus the
// interpolation's own 0.02). Step 2 makes the difference plain.
TEST_F(GlTest, BisectionRefinesTheHitToATenthOfAVoxel) {
    const Volume v = makePhantom("phantom:sphere:" + std::to_string(kN));
    const double radius = spherePhantomRadius(kN);
    const double step = 2.0;
    for (const CameraSpec& cam : {axisCamera("+z"), orbitCamera(30.0, 20.0)}) {
        SCOPED_TRACE(cam.view.empty() ? "orbit" : cam.view);
        const int size = cam.view.empty() ? 64 : kN;
        const DepthError coarse = depthError(v, isoScene(cam, size, step, 0), radius);
        const DepthError fine = depthError(v, isoScene(cam, size, step, 8), radius);
        std::printf("[ measured ] %s step %.0f: max |t - t_analytic| = %.4f voxel unrefined, %.4f with 8 steps\n",
                    cam.view.empty() ? "orbit 30/20" : cam.view.c_str(), step, coarse.maxError, fine.maxError);
        EXPECT_EQ(coarse.missed, 0);
        EXPECT_EQ(fine.missed, 0);
        // Unrefined: late by less than a step (plus the 0.05 interpolation
        // error), and by a good fraction of it somewhere over ~700 rays.
        EXPECT_LT(coarse.maxError, step + 0.05) << coarse.worst;
        EXPECT_GT(coarse.maxError, 0.5 * step) << coarse.worst;
        EXPECT_LT(fine.maxError, kRefinedTolerance) << fine.worst;
        EXPECT_GT(coarse.maxError, 4.0 * fine.maxError);
    }
}

// Where the ray enters the box [0, extent] (the slab method, written here):
// the largest of the per-axis entry distances, never behind the origin.
double boxEntry(glm::dvec3 o, glm::dvec3 d, glm::dvec3 extent) {
    double entry = 0.0;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) continue;
        const double t0 = (0.0 - o[a]) / d[a], t1 = (extent[a] - o[a]) / d[a];
        entry = std::max(entry, std::min(t0, t1));
    }
    return entry;
}

// Without refinement the reported hit is a sample: the first one past the
// crossing. Samples sit at t_entry + (m + 1/2) step (README), so
// (t - t_entry) / step - 1/2 must be a whole number (to 1e-3: float
// arithmetic on distances ~100 is good to 1e-5), and the sample lies at or
// after the analytic crossing by less than a step (+-0.05 voxel for the
// trilinear surface's own deviation, 0.03 measured in oblique views).
TEST_F(GlTest, UnrefinedHitIsTheFirstSamplePastTheCrossing) {
    const Volume v = makePhantom("phantom:sphere:" + std::to_string(kN));
    const double radius = spherePhantomRadius(kN);
    const double step = 2.0;
    for (const CameraSpec& cam : {axisCamera("-y"), orbitCamera(30.0, 20.0)}) {
        SCOPED_TRACE(cam.view.empty() ? "orbit" : cam.view);
        const Scene scene = isoScene(cam, cam.view.empty() ? 64 : kN, step, 0);
        engine().setVolume(v);
        const Image img = engine().render(scene);
        const Camera camera = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
        int checked = 0, bad = 0;
        std::string first;
        for (int py = 0; py < scene.height; ++py)
            for (int px = 0; px < scene.width; ++px) {
                const SphereRay r = sphereRay(camera, px, py, 0.5 * v.extent(), radius);
                if (r.closest >= 0.9 * radius) continue;
                ++checked;
                const double t = depthToDistance(img.at(px, py).r, r, v.extent());
                const double m = (t - boxEntry(r.origin, r.direction, v.extent())) / step - 0.5;
                const bool onSample = std::abs(m - std::round(m)) < 1e-3;
                const bool late = t > r.tHit - 0.05 && t < r.tHit + step + 0.05;
                if (!(onSample && late) && bad++ == 0)
                    first = "pixel (" + std::to_string(px) + ", " + std::to_string(py) + "): t = " + std::to_string(t) +
                            " = sample " + std::to_string(m) + ", analytic " + std::to_string(r.tHit);
            }
        EXPECT_GT(checked, 400);  // 432 in the orbit, 718 in the axis view
        EXPECT_EQ(bad, 0) << first;
    }
}

// Colours: rays that miss the sphere show the background exactly; with
// depth=0 and shading=0 a hit is the chosen colour exactly (opaque, so the
// background adds nothing: rgb + 0 * background).
TEST_F(GlTest, MissesShowTheBackgroundAndUnshadedHitsTheColour) {
    const Volume v = makePhantom("phantom:sphere:" + std::to_string(kN));
    const double radius = spherePhantomRadius(kN);
    const glm::vec3 colour(0.2f, 0.6f, 0.9f), background(0.1f, 0.3f, 0.05f);
    for (int depth : {0, 1}) {
        SCOPED_TRACE("depth " + std::to_string(depth));
        Scene scene = isoScene(orbitCamera(30.0, 20.0), 64, 1.0, 8);
        scene.parameters["depth"] = depth;
        scene.parameters["shading"] = 0;
        scene.parameters["color_r"] = colour.r;
        scene.parameters["color_g"] = colour.g;
        scene.parameters["color_b"] = colour.b;
        scene.background = background;
        engine().setVolume(v);
        const Image img = engine().render(scene);
        const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
        int hits = 0, misses = 0, bad = 0;
        std::string first;
        for (int py = 0; py < scene.height; ++py)
            for (int px = 0; px < scene.width; ++px) {
                const SphereRay r = sphereRay(cam, px, py, 0.5 * v.extent(), radius);
                const glm::vec3 got(img.at(px, py));
                // Rays more than half a voxel outside the sphere never see a
                // value of 0.5 (the trilinear surface is within 0.03 of it);
                // rays half a voxel inside cross it.
                bool ok = true;
                if (r.closest > radius + 0.5) {
                    ++misses;
                    ok = got == background;
                } else if (r.closest < radius - 0.5) {
                    ++hits;
                    if (depth == 0) ok = got == colour;
                    else ok = got.r == got.g && got.g == got.b && got.r > 0.0f && got.r < 1.0f;
                }
                if (!ok && bad++ == 0)
                    first = "pixel (" + std::to_string(px) + ", " + std::to_string(py) + "): got (" +
                            std::to_string(got.r) + ", " + std::to_string(got.g) + ", " + std::to_string(got.b) +
                            "), closest approach " + std::to_string(r.closest);
            }
        EXPECT_GT(hits, 400);  // R is 12.9 pixels: about 520 hit pixels
        EXPECT_GT(misses, 1000);
        EXPECT_EQ(bad, 0) << first;
    }
}

// A ray that starts inside the surface: the region of interest keeps only
// z >= N/2, so in the +z view every ray through the sphere's equator disc
// enters the box inside the sphere. The hit is then the cut face itself:
// the first sample, half a step behind the face (iso.glsl: "report that
// first sample"); an implementation reporting the face itself would also be
// right, so the test accepts [t_face, t_face + step/2] (+-0.001 for float
// precision). Rays outside the disc meet only the back half of the sphere,
// which is smaller: no hit.
TEST_F(GlTest, RayStartingInsideShowsTheCutFace) {
    const Volume v = makePhantom("phantom:sphere:" + std::to_string(kN));
    const double radius = spherePhantomRadius(kN);
    const double step = 0.5;
    Scene scene = isoScene(axisCamera("+z"), kN, step, 8);
    scene.roi = RegionOfInterest{glm::dvec3(0.0, 0.0, kN / 2.0), glm::dvec3(kN)};
    engine().setVolume(v);
    const Image img = engine().render(scene);
    const Camera cam = Camera::make(scene.camera, v.extent(), scene.width, scene.height);
    int inside = 0, outside = 0, bad = 0;
    std::string first;
    for (int py = 0; py < scene.height; ++py)
        for (int px = 0; px < scene.width; ++px) {
            const SphereRay r = sphereRay(cam, px, py, 0.5 * v.extent(), radius);
            const double grey = img.at(px, py).r;
            bool ok = true;
            double t = 0.0, tFace = 0.0;
            if (r.closest < 0.9 * radius) {
                ++inside;
                tFace = (kN / 2.0 - r.origin.z) / r.direction.z;  // where the ray crosses z = N/2
                t = depthToDistance(grey, r, v.extent());
                ok = grey > 0.0 && t > tFace - 1e-3 && t < tFace + 0.5 * step + 1e-3;
            } else if (r.closest > radius + 0.5) {
                ++outside;
                ok = grey == 0.0;
            }
            if (!ok && bad++ == 0)
                first = "pixel (" + std::to_string(px) + ", " + std::to_string(py) + "): grey " +
                        std::to_string(grey) + ", t = " + std::to_string(t) + ", face at " + std::to_string(tFace);
        }
    EXPECT_GT(inside, 600);
    EXPECT_GT(outside, 500);
    EXPECT_EQ(bad, 0) << first;
}

}  // namespace
}  // namespace voxlab::testing
