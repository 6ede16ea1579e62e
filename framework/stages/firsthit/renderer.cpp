// voxlab stage firsthit: renderer "firsthit": closest-vessel projection.
#include "voxlab/renderers.h"

namespace voxlab {

class FirstHitRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::FirstHit; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
    ProfileModel profileModel() const override { return ProfileModel::FirstHit; }
    ProfileSettings profileSettings(const ParameterValues& values) const override;
};

namespace {
constexpr const char* kThreshold = "threshold";
}

std::string FirstHitRenderer::id() const { return "firsthit"; }

std::string FirstHitRenderer::description() const {
    return "first hit: the first sample at or above a threshold, by its value or its depth";
}

std::vector<ParameterSpec> FirstHitRenderer::parameters() const {
    ParameterSpec threshold{kThreshold, ParameterType::Float, 0.0, 1.0, 0.5,
                            "the value a sample must reach (data units; default: mid-range)"};
    threshold.dataUnits = true;
    return {threshold,
            {"depth", ParameterType::Bool, 0, 1, 0, "show the hit's depth (near white, far black) instead of its value"}};
}

EmptySpaceRule FirstHitRenderer::emptySpaceRule(const ParameterValues& values) const {
    // Nothing below the threshold can be the first hit.
    return {EmptySpaceRule::Kind::AtLeast, values.at(kThreshold)};
}

ProfileSettings FirstHitRenderer::profileSettings(const ParameterValues& values) const {
    return {values.at(kThreshold)};
}

}  // namespace voxlab

VOXLAB_RENDERERS(firsthit) { registry.add<voxlab::FirstHitRenderer>(); }
