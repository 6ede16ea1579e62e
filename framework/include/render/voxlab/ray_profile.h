// voxlab: the ray profile of one pixel, as the renderer's own shaders
// compute it.
//
// The classic figure of volume-rendering lectures: the samples along one
// pixel's ray plotted against depth (value, opacity per sample, accumulated
// opacity and colour, running maximum) and the point where the ray stopped.
// RenderEngine::profileRay() takes it from the engine's shaders, the
// student's stages among them, in an instrumented run
// (shaders/voxlab/profile.glsl): each fragment of a small target follows
// the pixel's ray cut after one more sample, so the stage's own loop gives
// the pixel after each sample. What a profile shows is therefore what the
// code under test does (a bug in mip.glsl shows in MIP's running maximum),
// not a model of what it should do. From the run:
//  - every sample's position along the ray and its value as the sampling
//    stage reads it;
//  - the pixel (premultiplied, before the background) if the ray ended
//    after the sample: `accumulated`;
//  - compositing (ProfileModel::Composite): each sample's colour and
//    opacity as the stage applied them, from two consecutive pixels
//    (front to back, A_i = A_{i-1} + (1 - A_{i-1}) a_i), and where the loop
//    stopped taking samples;
//  - MIP, MinIP, the mean: the value the entry shader displayed after each
//    sample (its running maximum, minimum or mean);
//  - first hit and the isosurface: the first sample after which the pixel
//    holds a hit.
// The ray is the one the renderer follows (jitter, the region of interest,
// clip planes, a cutting plane's half-space, a thin slab: as the entry
// shader clips it), with empty-space skipping off, as grading renders.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/renderer.h"
#include "voxlab/scene.h"
#include "voxlab/transfer_function.h"
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
    // after this sample: front-to-back compositing so far, or
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
    double threshold = 0.0;           // a first hit's threshold or the isovalue (data units)
    bool hasThreshold = false;
    double earlyTermination = 1.0;    // compositing's early-termination opacity
    double hitT = 0.0;                // where the surface or the first hit lies along the ray
    // The pixel's premultiplied colour and opacity before the background:
    // the renderer's output is result.rgb + (1 - result.a) * background.
    glm::vec4 result{0.0f};
};

// What the instrumented run read back (RenderEngine::profileRay), for
// fillRayProfile(): per sample kept, the pixel after it and the record
// (value, displayed value, t, samples of the whole ray); the whole ray's
// pixel; the whole ray's sample count (-1: the ray misses the region;
// kProfileStub: a stage's stub was reached).
inline constexpr int kProfileStub = -2;
inline constexpr int kProfileNoSamples = -3;  // the ray meets the region, but nothing asked sample_count()
struct ProfileReadings {
    std::vector<glm::vec4> accumulated, records;
    glm::vec4 result{0.0f};
    int samples = -1;
    double earlyTermination = 1.0;  // compositing's parameter (1: none)
    double threshold = 0.0;         // first hit's threshold or the isovalue
    const TransferFunction* tf = nullptr;  // how one value alone is shown (else grey through the window)
    glm::dvec2 window{0.0, 1.0};
};

// Fills `profile` (its pixel, renderer, model, step, origin and direction
// set) from the readings.
void fillRayProfile(RayProfile& profile, const ProfileReadings& readings);

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
