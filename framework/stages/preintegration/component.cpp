// voxlab stage preintegration: pre-integrated classification as a
// compositing component (voxlab/renderers.h): each segment between two
// samples classified by a table that preintegration_table.frag fills with
// the stage's preintegrate_segment().
#include <string>

#include "voxlab/renderers.h"
#include "voxlab/scene.h"

namespace voxlab {
namespace {

// The table's size, texels on each axis (the stage's PREINTEGRATION_TABLE_SIZE).
constexpr int kTableSize = 256;

class PreintegrationComponent final : public CompositeComponent {
public:
    Phase phase() const override { return Phase::Classify; }
    std::vector<ParameterSpec> parameters() const override {
        return {{"preintegrated", ParameterType::Bool, 0, 1, 0,
                 "classify each segment between two samples by a pre-integrated table (fewer samples, no slicing)"}};
    }
    // A segment reaches the next sample, which may lie in the next brick;
    // and a skipped brick could cut a segment of a visible one short.
    bool readsBeyondBrick() const override { return true; }
    bool keepsSkipping() const override { return false; }
    bool classifies() const override { return true; }
    // The table depends on the transfer function (the engine watches it) and
    // on the segment's length, the step.
    std::vector<Precomputation> precomputations(const Scene& scene, const Volume&,
                                                const ParameterValues&) const override {
        return {{"u_preintegration_table", "stages/preintegration/preintegration_table.frag",
                 glm::ivec3(kTableSize, kTableSize, 1), 4, "step=" + std::to_string(scene.step)}};
    }
};

}  // namespace
}  // namespace voxlab

VOXLAB_COMPOSITE_COMPONENTS(preintegration) { components.add<voxlab::PreintegrationComponent>(); }
