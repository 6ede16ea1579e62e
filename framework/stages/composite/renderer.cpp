// voxlab stage composite: renderer "composite": direct volume rendering (emission-absorption)
// with the 1D transfer function.
#include "voxlab/renderers.h"

#include <cstdio>

#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/volume.h"

namespace voxlab {

// The pre-integration table's size, texels on each axis (the preintegration
// stage's PREINTEGRATION_TABLE_SIZE).
constexpr int kPreintegrationTableSize = 256;
// The light volume of the shadows stage: the volume's dimensions, at most
// `resolution` voxels on each axis (composite's `shadow_resolution`).

class CompositeRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues& values) const override;
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool needsTransferFunction() const override { return true; }
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
    ProfileModel profileModel() const override { return ProfileModel::Composite; }
    ProfileSettings profileSettings(const ParameterValues& values) const override {
        return compositingProfileSettings(values);
    }
    std::vector<Precomputation> precomputations(const Scene& scene, const Volume& volume,
                                                const ParameterValues& values) const override;
    void checkScene(const Scene& scene, const ParameterValues& values) const override;
};

std::string CompositeRenderer::id() const { return "composite"; }

std::string CompositeRenderer::description() const {
    return "direct volume rendering: front-to-back compositing through the 1D transfer function";
}

std::vector<ParameterSpec> CompositeRenderer::parameters() const {
    std::vector<ParameterSpec> p = compositingParameters();
    p.push_back({"preclassify", ParameterType::Bool, 0, 1, 0,
                 "classify the voxels, then interpolate colours (pre-classification)"});
    // Boundary emphasis (the gradient_opacity stage): the bounds are
    // gradient magnitudes, data units per unit length, given here as
    // fractions of the value range's width (dataSpan).
    p.push_back({"gradient_opacity", ParameterType::Bool, 0, 1, 0,
                 "multiply opacity by a ramp of the gradient magnitude: homogeneous regions fade, boundaries stay"});
    ParameterSpec low{"gradient_low", ParameterType::Float, 0.0, 0.5, 0.01,
                      "gradient opacity: at or below this gradient magnitude, no opacity (data units per unit length)"};
    ParameterSpec high{"gradient_high", ParameterType::Float, 0.0, 0.5, 0.08,
                       "gradient opacity: at or above this gradient magnitude, full opacity (data units per unit length)"};
    low.dataSpan = high.dataSpan = true;
    p.push_back(low);
    p.push_back(high);
    // Local ambient occlusion (the ambient_occlusion stage).
    p.push_back({"ambient_occlusion", ParameterType::Bool, 0, 1, 0,
                 "darken each sample by the mean opacity around it (local ambient occlusion)"});
    p.push_back({"ao_radius", ParameterType::Float, 0.5, 16, 3,
                 "ambient occlusion: how far around the sample to look, in smallest spacings"});
    p.push_back({"ao_strength", ParameterType::Float, 0, 1, 0.8,
                 "ambient occlusion: how much a fully surrounded sample is darkened"});
    // Pre-integrated classification (the preintegration stage).
    p.push_back({"preintegrated", ParameterType::Bool, 0, 1, 0,
                 "classify each segment between two samples by a pre-integrated table (fewer samples, no slicing)"});
    // Shadows from a light volume (the shadows stage).
    p.push_back({"shadows", ParameterType::Bool, 0, 1, 0,
                 "dim each lit sample by the transmittance towards the light (a light volume; turn the light "
                 "away from the view to see them)"});
    // The light volume is computed again whenever the camera turns (the
    // light turns with it): on the bonsai, 64 per axis costs about 0.1 s a
    // time, 128 about 0.7 s (docs/performance.md).
    p.push_back({"shadow_resolution", ParameterType::Int, 16, 256, 64,
                 "shadows: the light volume's voxels along each axis, at most (finer shadows, slower to compute)"});
    for (ParameterSpec& s : shadingParameters(false)) p.push_back(s);
    return p;
}

namespace {
// The light volume of the shadows stage: the volume's dimensions, at most
// `resolution` voxels on each axis (`shadow_resolution`).
glm::ivec3 lightVolumeSize(glm::ivec3 dims, int resolution) { return glm::min(dims, glm::ivec3(resolution)); }

bool on(const ParameterValues& values, const char* name) {
    const auto it = values.find(name);
    return it != values.end() && it->second != 0.0;
}
}  // namespace

// A label map and a second volume replace the classification (each sample
// by its label, or by both volumes), so the other ways of classifying do not
// combine with them.
void CompositeRenderer::checkScene(const Scene& scene, const ParameterValues& values) const {
    const char* other = scene.labels ? "a label map (scene \"labels\")" : "a fused volume (scene \"fusion\")";
    if (!scene.labels && !scene.fusion) return;
    for (const char* name : {"preintegrated", "preclassify"})
        if (on(values, name))
            throw Error(std::string("composite: parameter '") + name + "' does not combine with " + other);
}

// Composited front to back, brick after brick. Three options read beyond
// a brick's apron: ambient occlusion up to 16 voxels around a sample, the
// light volume of shadows the whole volume, and a pre-integrated segment the
// next sample, which may lie in the next brick.
BrickCombine CompositeRenderer::brickCombine(const ParameterValues& values) const {
    for (const char* name : {"ambient_occlusion", "shadows", "preintegrated"})
        if (on(values, name))
            throw Error(std::string("composite: parameter '") + name +
                        "' reads beyond one brick and does not combine with a bricked volume");
    return BrickCombine::Over;
}

// A pre-integrated segment reaches from its sample to the next one, which
// may lie in a brick that a skipped one borders: skipping would drop the
// part of the segment in the visible brick. So it is off for them.
EmptySpaceRule CompositeRenderer::emptySpaceRule(const ParameterValues& values) const {
    if (on(values, "preintegrated")) return {EmptySpaceRule::Kind::None};
    return {EmptySpaceRule::Kind::TransferFunction};
}

// The pre-integration table depends on the transfer function (the engine
// watches it) and on the segment's length, the step.
std::vector<Precomputation> CompositeRenderer::precomputations(const Scene& scene, const Volume& volume,
                                                               const ParameterValues& values) const {
    std::vector<Precomputation> list;
    if (on(values, "preintegrated"))
        list.push_back({"u_preintegration_table", "stages/preintegration/preintegration_table.frag",
                        glm::ivec3(kPreintegrationTableSize, kPreintegrationTableSize, 1), 4,
                        "step=" + std::to_string(scene.step)});
    if (on(values, "shadows")) {
        // The light turns with the camera (lighting.glsl): its direction is
        // fixed by the camera's axes and the two light angles.
        const Camera cam = Camera::make(scene.camera, volume.extent(), scene.width, scene.height);
        char key[256];
        std::snprintf(key, sizeof key, "f=%.7g,%.7g,%.7g r=%.7g,%.7g,%.7g d=%.7g,%.7g,%.7g light=%.7g,%.7g",
                      cam.forward.x, cam.forward.y, cam.forward.z, cam.right.x, cam.right.y, cam.right.z, cam.down.x,
                      cam.down.y, cam.down.z, values.at("light_azimuth"), values.at("light_elevation"));
        list.push_back({"u_light_volume", "stages/shadows/light_volume.frag", lightVolumeSize(volume.dims(), int(values.at("shadow_resolution"))), 1, key});
    }
    return list;
}

}  // namespace voxlab

VOXLAB_RENDERERS(composite) { registry.add<voxlab::CompositeRenderer>(); }
