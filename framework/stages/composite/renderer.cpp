// voxlab stage composite: renderer "composite": direct volume rendering (emission-absorption)
// with the 1D transfer function.
#include "voxlab/renderers.h"

#include "voxlab/error.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume.h"

namespace voxlab {

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
    // Its components' GLSL, called where each is switched on.
    std::map<std::string, std::string> generatedShaders() const override {
        return {{"stages/composite/components.glsl", compositeComponentsGlsl()}};
    }
};

std::string CompositeRenderer::id() const { return "composite"; }

std::string CompositeRenderer::description() const {
    return "direct volume rendering: front-to-back compositing through the 1D transfer function";
}

std::vector<ParameterSpec> CompositeRenderer::parameters() const {
    std::vector<ParameterSpec> p = compositingParameters();
    p.push_back({"preclassify", ParameterType::Bool, 0, 1, 0,
                 "classify the voxels, then interpolate colours (pre-classification)"});
    // The features other stages bring (their folders' component.cpp).
    for (const auto& component : compositeComponents().all())
        for (ParameterSpec& s : component->parameters()) p.push_back(s);
    for (ParameterSpec& s : shadingParameters(false)) p.push_back(s);
    return p;
}

// A label map and a second volume replace the classification (each sample
// by its label, or by both volumes), so the other ways of classifying do not
// combine with them.
void CompositeRenderer::checkScene(const Scene& scene, const ParameterValues& values) const {
    if (!scene.labels && !scene.fusion) return;
    const char* other = scene.labels ? "a label map (scene \"labels\")" : "a fused volume (scene \"fusion\")";
    auto refuse = [&](const std::string& name) {
        throw Error("composite: parameter '" + name + "' does not combine with " + other);
    };
    for (const auto& component : compositeComponents().all())
        if (component->classifies() && component->on(values)) refuse(component->switchName());
    if (parameterOn(values, "preclassify")) refuse("preclassify");
}

// Composited front to back, brick after brick, unless a component reads
// beyond a brick's apron.
BrickCombine CompositeRenderer::brickCombine(const ParameterValues& values) const {
    for (const auto& component : compositeComponents().all())
        if (component->readsBeyondBrick() && component->on(values))
            throw Error("composite: parameter '" + component->switchName() +
                        "' reads beyond one brick and does not combine with a bricked volume");
    return BrickCombine::Over;
}

EmptySpaceRule CompositeRenderer::emptySpaceRule(const ParameterValues& values) const {
    for (const auto& component : compositeComponents().all())
        if (!component->keepsSkipping() && component->on(values)) return {EmptySpaceRule::Kind::None};
    return {EmptySpaceRule::Kind::TransferFunction};
}

std::vector<Precomputation> CompositeRenderer::precomputations(const Scene& scene, const Volume& volume,
                                                               const ParameterValues& values) const {
    std::vector<Precomputation> list;
    for (const auto& component : compositeComponents().all())
        if (component->on(values))
            for (Precomputation& p : component->precomputations(scene, volume, values)) list.push_back(p);
    return list;
}

}  // namespace voxlab

VOXLAB_RENDERERS(composite) { registry.add<voxlab::CompositeRenderer>(); }
