// voxlab stage ambient_occlusion: local ambient occlusion as a compositing
// component (voxlab/renderers.h): each sample darkened by the mean opacity
// around it, up to 16 voxels away.
#include "voxlab/renderers.h"

namespace voxlab {
namespace {

class AmbientOcclusionComponent final : public CompositeComponent {
public:
    Phase phase() const override { return Phase::Lit; }
    std::vector<ParameterSpec> parameters() const override {
        return {{"ambient_occlusion", ParameterType::Bool, 0, 1, 0,
                 "darken each sample by the mean opacity around it (local ambient occlusion)"},
                {"ao_radius", ParameterType::Float, 0.5, 16, 3,
                 "ambient occlusion: how far around the sample to look, in smallest spacings"},
                {"ao_strength", ParameterType::Float, 0, 1, 0.8,
                 "ambient occlusion: how much a fully surrounded sample is darkened"}};
    }
    // It reads up to 16 voxels around a sample: beyond a brick's apron.
    bool readsBeyondBrick() const override { return true; }
};

}  // namespace
}  // namespace voxlab

VOXLAB_COMPOSITE_COMPONENTS(ambient_occlusion) { components.add<voxlab::AmbientOcclusionComponent>(); }
