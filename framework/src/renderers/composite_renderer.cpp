// voxlab renderer "composite": direct volume rendering (emission-absorption)
// with the 1D transfer function.
#include "voxlab/renderers.h"

namespace voxlab {

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
    for (ParameterSpec& s : shadingParameters(false)) p.push_back(s);
    return p;
}

namespace {
bool on(const ParameterValues& values, const char* name) {
    const auto it = values.find(name);
    return it != values.end() && it->second != 0.0;
}
}  // namespace

// A pre-integrated segment reaches from its sample to the next one, which
// may lie in a brick that a skipped one borders: skipping would drop the
// part of the segment in the visible brick. So it is off for them.
EmptySpaceRule CompositeRenderer::emptySpaceRule(const ParameterValues& values) const {
    if (on(values, "preintegrated")) return {EmptySpaceRule::Kind::None};
    return {EmptySpaceRule::Kind::TransferFunction};
}

// The pre-integration table depends on the transfer function (the engine
// watches it) and on the segment's length, the step.
std::vector<Precomputation> CompositeRenderer::precomputations(const Scene& scene, const Volume&,
                                                               const ParameterValues& values) const {
    std::vector<Precomputation> list;
    if (on(values, "preintegrated"))
        list.push_back({"u_preintegration_table", "precompute/preintegration_table.frag",
                        glm::ivec3(kPreintegrationTableSize, kPreintegrationTableSize, 1), 4,
                        "step=" + std::to_string(scene.step)});
    return list;
}

}  // namespace voxlab
