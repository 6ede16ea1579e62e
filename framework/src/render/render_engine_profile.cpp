// voxlab: the ray profile from the engine's own shaders (see
// voxlab/ray_profile.h and shaders/voxlab/profile.glsl).
//
// Four draws of the scene's pass, with skipping off, into a target of one
// fragment per sample (rows of at most kRowWidth): the whole ray's record
// (one fragment whose sample lies past the ray's end: the ray's sample
// count and the last displayed value) and its pixel; then, for every
// sample i, the pixel and the record of the ray cut after sample i. A ray
// of n samples costs about n^2 / 2 samples in all: for the largest profile
// (kMaxSamples) a few hundred million, a second or so on llvmpipe.
#include <algorithm>
#include <optional>
#include <string>

#include "engine_internal.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/render_engine.h"
#include "volume_textures.h"
#include "voxlab_gl.h"

namespace voxlab {

namespace {
constexpr int kRowWidth = 1024;
constexpr int kMaxSamples = 8192;  // the profile keeps the first ones of a longer ray
constexpr int kPastTheEnd = 1 << 30;  // a sample index beyond any ray
}  // namespace

std::vector<glm::vec4> RenderEngine::drawProfilePass(const Scene& scene, const Pass& pass, int which, int first,
                                                     int count) {
    const int width = std::min(count, kRowWidth), height = (count + width - 1) / width;
    // The target only grows: a profile's four passes draw into its corner.
    if (!profileTarget_.made() || profileTargetSize_.x < width || profileTargetSize_.y < height) {
        profileTargetSize_ = glm::max(profileTargetSize_, glm::ivec2(width, height));
        profileTarget_.make(profileTargetSize_.x, profileTargetSize_.y);
    }
    std::vector<glm::vec4> out(std::size_t(width) * std::size_t(height));
    profilePass_ = which, profileWidth_ = width, profileFirst_ = first;
    try {
        glBindFramebuffer(GL_FRAMEBUFFER, profileTarget_.framebuffer);
        glViewport(0, 0, width, height);
        draw(scene, pass);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, out.data());
        checkGlError("reading back the ray profile");
    } catch (...) {
        profilePass_ = 0;
        throw;
    }
    profilePass_ = 0;
    out.resize(std::size_t(count));  // fragment (x, y) holds sample y * width + x: the rows in order
    return out;
}

RayProfile RenderEngine::profileRay(const Scene& given, int px, int py) {
    if (!volume_) throw Error("ray profile: no volume has been set");
    if (px < 0 || py < 0 || px >= given.width || py >= given.height)
        throw Error("ray profile: pixel (" + std::to_string(px) + ", " + std::to_string(py) + ") is outside the " +
                    std::to_string(given.width) + "x" + std::to_string(given.height) + " image");
    Scene scene = given;
    scene.skipEmptySpace = false;  // sample for sample, as grading renders
    const Pass pass = scenePass(scene);
    RayProfile profile;
    profile.px = px, profile.py = py;
    profile.renderer = pass.renderer->id();
    profile.model = pass.renderer->profileModel();
    profile.stepUnits = scene.step;
    profile.step = scene.step * volume_->minSpacing();
    Camera::make(scene.camera, volume_->extent(), scene.width, scene.height)
        .ray(px + 0.5, py + 0.5, &profile.origin, &profile.direction);
    if (pass.renderer->objectOrder()) {
        profile.why = profile.renderer + " draws slices, not rays: there is no ray to follow";
        return profile;
    }
    volumeTextures_->set(*volume_, volumeGeneration_, budgetFor(scene), maxTextureSize_);
    if (volumeTextures_->layout().bricked()) {
        profile.why = "the volume is drawn in bricks, and the profile follows a ray through one texture "
                      "(give the scene more GPU memory: gpu_memory)";
        return profile;
    }

    // The profile's draws leave what the last render noted (its sources,
    // its stubs) and the image's tile as they were, thrown through or not.
    struct Kept {
        RenderEngine& e;
        std::vector<std::string> sources = e.lastRenderSources_, stubs = e.lastRenderStubs_,
                                 mainStubs = e.mainProgramStubs_;
        int noted = e.programsNoted_;
        std::optional<glm::ivec4> tile = std::exchange(e.tile_, std::nullopt);
        ~Kept() {
            e.lastRenderSources_ = sources, e.lastRenderStubs_ = stubs, e.mainProgramStubs_ = mainStubs;
            e.programsNoted_ = noted, e.tile_ = tile;
        }
    };
    ProfileReadings in;
    {
        const Kept kept{*this};
        profilePixel_ = glm::vec2(px, py);
        in.samples = int(drawProfilePass(scene, pass, 2, kPastTheEnd, 1)[0].w);
        in.result = drawProfilePass(scene, pass, 1, kPastTheEnd, 1)[0];
        const int count = std::min(std::max(in.samples, 0), kMaxSamples);
        if (count > 0) {
            in.accumulated = drawProfilePass(scene, pass, 1, 0, count);
            in.records = drawProfilePass(scene, pass, 2, 0, count);
        }
    }
    const ProfileSettings settings = pass.renderer->profileSettings(pass.values);
    in.earlyTermination = settings.earlyTermination;
    in.threshold = settings.threshold;
    if (scene.cuttingPlane && scene.cuttingPlane->otherRenderer != "none")
        profile.note = "cutting plane: only " + profile.renderer + "'s half-space is followed, not " +
                       scene.cuttingPlane->otherRenderer + "'s";
    std::optional<TransferFunction> fallback;
    in.tf = passInputs(scene, pass, fallback).tf;
    in.window = scene.window.value_or(volume_->valueRange());
    fillRayProfile(profile, in);
    return profile;
}

}  // namespace voxlab
