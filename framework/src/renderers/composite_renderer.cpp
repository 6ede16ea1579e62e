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
    for (ParameterSpec& s : shadingParameters(false)) p.push_back(s);
    return p;
}

EmptySpaceRule CompositeRenderer::emptySpaceRule(const ParameterValues&) const {
    return {EmptySpaceRule::Kind::TransferFunction};
}

}  // namespace voxlab
