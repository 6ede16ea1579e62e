// voxlab: the ray profile of one pixel, computed on the CPU.
//
// The classic figure of volume-rendering lectures: the samples along one
// pixel's ray plotted against depth (value, opacity per sample, accumulated
// opacity and colour, running maximum) and the point where the ray stopped.
// computeRayProfile() follows the ray the way the ray-casting renderers do
// (README, "Rendering conventions"), independently of their GLSL:
//  - the ray from Camera::make + Camera::ray through the pixel's centre,
//    clipped to the volume's box cropped by the scene's roi and clip planes (and, for
//    slab_mip, to the slab; for a cutting plane, to the scene renderer's
//    half-space);
//  - samples at t_entry + (m + 1/2) step for floor((t_exit - t_entry)/step + 1/2)
//    values of m, read by nearest or trilinear interpolation ("hardware" is
//    read as trilinear: the GPU's 8-bit weights are not modelled);
//  - composite: the scene's transfer function (or the engine's fallback, a
//    white ramp over the window from opacity 0 to 0.1 per unit length),
//    opacity-corrected for the step, pre- or post-classified, Phong-shaded
//    when `shading` is on, composited front to back until the accumulated
//    opacity reaches `early_termination` (jitter moves the start as the GPU
//    does, by the same per-pixel hash); with the optional stages as their
//    handouts define them: gradient opacity, ambient occlusion,
//    pre-integration (each segment integrated in double, where the GPU
//    interpolates a table) and shadows (each sample's shadow ray followed,
//    where the GPU interpolates a light volume: they differ where the
//    transmittance jumps within one light-volume voxel); with a label map or
//    a fused second volume, each sample classified as the labels handout and
//    scene.h define them (ray_profile_scene.cpp);
//  - mip, slab_mip, minip, average: running maximum, minimum, mean, shown
//    through the window or the transfer function;
//  - firsthit: the first sample at or above `threshold`;
//  - iso: the first sign change of value - isovalue between two samples,
//    refined by bisection, shaded.
// Renderers it does not model (texslice2d, texslice3d, tf2d, slicer) give the
// ray and the samples' values only; `why` says "not modelled for <renderer>".
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/renderer.h"
#include "voxlab/scene.h"
#include "voxlab/volume.h"

namespace voxlab {

struct RaySample {
    double t = 0.0;                  // distance along the ray (world units)
    glm::dvec3 position{0.0};        // world position
    double value = 0.0;              // interpolated value, data units
    // Compositing renderers: the sample's colour (rgb, not premultiplied;
    // shaded when shading is on) and its opacity corrected for the step.
    // Projection renderers: how this sample's value alone would be shown
    // (grey through the window, or the transfer function's colour and
    // opacity, uncorrected).
    glm::vec4 classified{0.0f};
    // Premultiplied colour and opacity the pixel would have if the ray ended
    // after this sample: front-to-back compositing so far (composite), or
    // the display of the running maximum / minimum / mean / first hit.
    glm::vec4 accumulated{0.0f};
    double runningMax = 0.0, runningMin = 0.0, runningMean = 0.0;  // over samples 0..this one
};

struct RayProfile {
    int px = 0, py = 0;               // the pixel (py counted downwards)
    bool hitsVolume = false;          // the ray meets the sampled region
    glm::dvec3 origin{0.0}, direction{0.0, 0.0, 1.0};  // the ray (direction unit length)
    double tEntry = 0.0, tExit = 0.0;  // the clipped ray (after jitter: tEntry is the first sample's base)
    double step = 0.0;                // world units
    double stepUnits = 0.0;           // the scene's step, in units of the smallest spacing
    std::vector<RaySample> samples;   // every sample the ray would take, in order (also those after a stop)
    std::string renderer;
    ProfileModel model = ProfileModel::None;  // the renderer's (Renderer::profileModel); Composite on a
                                              // ray that hits: classified/accumulated hold compositing
    bool modelled = false;            // `result` is what the renderer computes
    int stoppedAt = -1;               // index of the last sample used; -1: all of them
    int chosen = -1;                  // the sample that gives the pixel its value (maximum, minimum, hit); -1: none
    std::string why;                  // why the ray stopped, in words
    std::string note;                 // what the profile leaves out, if anything ("" when exact)
    double threshold = 0.0;           // firsthit's threshold or iso's isovalue (data units)
    bool hasThreshold = false;
    double earlyTermination = 1.0;    // composite's early-termination opacity
    double hitT = 0.0;                // iso/firsthit: where the surface or hit lies along the ray
    // The pixel's premultiplied colour and opacity before the background:
    // the renderer's output is result.rgb + (1 - result.a) * background.
    glm::vec4 result{0.0f};
};

// Follows the ray of pixel (px, py) of `scene` through `volume` (the scene's
// dataset is ignored). Throws voxlab::Error for a pixel outside the image or
// an unknown renderer.
RayProfile computeRayProfile(const Volume& volume, const Scene& scene, int px, int py);

// The samples a frame of `scene` takes by the README's rule, summed over its
// pixels: floor(length / step + 1/2) per ray over the part inside the box
// and the region of interest (cutting planes and slabs, which shorten rays
// further, are not counted). What a ray caster without any skipping takes;
// `voxlab bench` and the viewer's samples view compare it with the samples
// counted on the GPU.
double samplesByRule(const Volume& volume, const Scene& scene);

// The pixel the renderer would show: `profile.result` over `background`.
glm::vec3 profilePixel(const RayProfile& profile, const glm::vec3& background);

}  // namespace voxlab
