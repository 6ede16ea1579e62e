// voxlab stage tf2d: renderer "tf2d": direct volume rendering classified by the 2D
// transfer function over (value, gradient magnitude).
#include "voxlab/renderers.h"

namespace voxlab {

class Tf2dRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::Over; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool needsTransferFunction2D() const override { return true; }
    bool usesTransferFunction() const override { return false; }
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
    ProfileModel profileModel() const override { return ProfileModel::Composite; }
    ProfileSettings profileSettings(const ParameterValues& values) const override {
        return compositingProfileSettings(values);
    }
};

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

VOXLAB_RENDERERS(tf2d) { registry.add<voxlab::Tf2dRenderer>(); }
