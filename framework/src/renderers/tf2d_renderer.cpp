// voxlab renderer "tf2d": direct volume rendering classified by the 2D
// transfer function over (value, gradient magnitude).
#include "voxlab/renderers.h"

namespace voxlab {

std::string Tf2dRenderer::id() const { return "tf2d"; }

std::string Tf2dRenderer::description() const {
    return "direct volume rendering through the 2D transfer function (value x gradient magnitude)";
}

std::vector<ParameterSpec> Tf2dRenderer::parameters() const {
    std::vector<ParameterSpec> p = compositingParameters();
    for (ParameterSpec& s : shadingParameters(true)) p.push_back(s);
    return p;
}

// The samples' gradient estimator, for the bricks' tight gradient bounds;
// precomputed gradients: none (the bound that holds for any).
EmptySpaceRule Tf2dRenderer::emptySpaceRule(const ParameterValues& values) const {
    EmptySpaceRule rule{EmptySpaceRule::Kind::TransferFunction2D};
    rule.gradients = onTheFlyGradients(values);
    return rule;
}

}  // namespace voxlab
