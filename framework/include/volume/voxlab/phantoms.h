// voxlab: built-in analytic test volumes ("phantoms").
//
// Addressed as "phantom:NAME[:SIZE]" through loadVolume() or makePhantom()
// (declared in volume.h). SIZE is the edge length N in voxels (default 64,
// allowed 2..512); every phantom is an N x N x N volume with spacing 1, so
// voxel (i,j,k) has its centre at world position p = (i+1/2, j+1/2, k+1/2)
// and the volume's centre is c = (N/2, N/2, N/2).
//
// Phantoms, with their formulas:
//
//  sphere          float32. Let r = |p - c|, R = 0.35 N and W = 4 voxels.
//                  value = clamp(0.5 + (R - r) / W, 0, 1): 1 inside, 0
//                  outside, with a linear ramp of width W across the
//                  surface, so the 0.5 isosurface is exactly the sphere of
//                  radius R and the gradient there is 1/W along -r.
//  shells          uint8. Three concentric shells of thickness
//                  t = max(1, N/16) centred on radii 0.15 N, 0.28 N and
//                  0.42 N (a voxel is in a shell when |r - radius| <= t/2),
//                  with values 80, 160 and 240; background 0.
//  marschner-lobb  float32. Marschner & Lobb's test signal (1994) on
//                  [-1,1]^3, voxel centres mapped by x = -1 + 2(i+1/2)/N:
//                  rho = (1 - sin(pi z/2) + a (1 + cos(2 pi fM cos(pi r/2))))
//                        / (2 (1 + a)),  r = sqrt(x^2 + y^2), fM = 6, a = 0.25.
//                  Values lie in [0, 1].
//  shepp-logan     float32. A 3D Shepp-Logan head: ten ellipsoids in [-1,1]^3
//                  (same mapping as above), each adding its density inside
//                  it; the "modified" high-contrast densities (outer skull
//                  1.0, brain -0.8, ventricles -0.2, small features +0.1),
//                  clamped to >= 0. Brain tissue is 0.2, features 0.3, air 0.
//  ct-signed       int16, in Hounsfield units, like a CT: air -1000
//                  outside r > 0.45 N; a soft-tissue shell of 40 for
//                  0.40 N < r <= 0.45 N; fat -100 for 0.25 N < r <= 0.40 N; a
//                  bone core of 700 for r <= 0.25 N; and an air pocket of
//                  -800 of radius 0.08 N centred at c + (0.32 N, 0, 0), inside
//                  the fat. Rays that miss the body see only -1000: every
//                  value on them is negative, so a maximum started at 0 (or
//                  a minimum at 0 where all are positive) shows.
//  sphere-over-slab float32, a scene for shadowing. A slab of value 1 fills
//                  0.10 N <= z <= 0.25 N (all x and y); a sphere of value
//                  0.5 and radius 0.15 N floats above it, centred at
//                  (N/2, N/2, 0.6 N); elsewhere 0. Lit from +z, the sphere
//                  casts a disc-shaped shadow of radius 0.15 N on the slab.
//  nested-labels   float32 holding whole numbers: a label map (tagged volume
//                  rendering). Label 2 inside the sphere of radius 0.18 N
//                  centred at c + (0.12 N, 0, 0); label 1 in the rest of the
//                  sphere of radius 0.40 N centred at c (which holds the
//                  first); 0 (no label) elsewhere.
//  ramp-x/y/z      float32. value = the voxel centre's coordinate along that
//                  axis (i+1/2, j+1/2 or k+1/2): a field with gradient
//                  exactly 1 along one axis, for sampling and gradient tests.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace voxlab {

constexpr int kPhantomDefaultSize = 64;
constexpr int kPhantomMinSize = 2;
constexpr int kPhantomMaxSize = 512;

// --- sphere ------------------------------------------------------------------
// Width W (in voxels) of the linear ramp across the sphere's surface.
constexpr double kSpherePhantomWidth = 4.0;
// Radius R = 0.35 N of the 0.5 isosurface.
inline double spherePhantomRadius(int n) { return 0.35 * n; }
inline double spherePhantomWidth() { return kSpherePhantomWidth; }
// The sphere's value at world position p (voxel units) for edge length n,
// before the conversion to float32 that the volume stores.
double spherePhantomValue(int n, glm::dvec3 p);

// --- shells ------------------------------------------------------------------
inline double shellsPhantomThickness(int n) { return n / 16.0 > 1.0 ? n / 16.0 : 1.0; }

// --- sphere-over-slab ----------------------------------------------------------
// Its value at world position p (voxel units) for edge length n.
double sphereOverSlabValue(int n, glm::dvec3 p);
inline double sphereOverSlabRadius(int n) { return 0.15 * n; }
inline glm::dvec3 sphereOverSlabCentre(int n) { return {n / 2.0, n / 2.0, 0.6 * n}; }

// --- nested-labels -------------------------------------------------------------
// The label at world position p (voxel units) for edge length n.
int nestedLabelsValue(int n, glm::dvec3 p);

// --- ct-signed ---------------------------------------------------------------
// Its value (Hounsfield units) at world position p for edge length n.
int ctSignedPhantomValue(int n, glm::dvec3 p);

// --- Marschner-Lobb ----------------------------------------------------------
constexpr double kMarschnerLobbFM = 6.0;
constexpr double kMarschnerLobbAlpha = 0.25;
// The test signal at (x, y, z) in [-1,1]^3.
double marschnerLobbValue(double x, double y, double z);

// --- Shepp-Logan ---------------------------------------------------------------
// The (unclamped sum, then clamped) density at q in [-1,1]^3.
double sheppLoganValue(glm::dvec3 q);

}  // namespace voxlab
