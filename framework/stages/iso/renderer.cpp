// voxlab stage iso: renderer "iso": isosurface ray casting with bisection refinement.
#include "voxlab/renderers.h"

namespace voxlab {

class IsoRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::FirstHit; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
    ProfileModel profileModel() const override { return ProfileModel::Isosurface; }
    ProfileSettings profileSettings(const ParameterValues& values) const override;
    bool usesTransferFunction() const override { return false; }
};

namespace {
constexpr const char* kIsovalue = "isovalue";
}

std::string IsoRenderer::id() const { return "iso"; }

std::string IsoRenderer::description() const {
    return "isosurface: the first crossing of an isovalue, refined by bisection and shaded";
}

std::vector<ParameterSpec> IsoRenderer::parameters() const {
    using T = ParameterType;
    ParameterSpec isovalue{kIsovalue, T::Float, 0.0, 1.0, 0.5, "the surface's value (data units; default: mid-range)"};
    isovalue.dataUnits = true;
    std::vector<ParameterSpec> p = {
        isovalue,
        {"refinement_steps", T::Int, 0, 32, 8, "bisection steps between the two samples around the crossing"},
        {"color_r", T::Float, 0, 1, 0.9, "surface colour, red"},
        {"color_g", T::Float, 0, 1, 0.85, "surface colour, green"},
        {"color_b", T::Float, 0, 1, 0.75, "surface colour, blue"},
        {"depth", T::Bool, 0, 1, 0, "show the hit's depth (near white, far black) instead of the shaded colour"},
    };
    for (ParameterSpec& s : shadingParameters(true)) p.push_back(s);
    return p;
}

EmptySpaceRule IsoRenderer::emptySpaceRule(const ParameterValues& values) const {
    // A ray can only meet the surface where some value reaches the isovalue.
    return {EmptySpaceRule::Kind::AtLeast, values.at(kIsovalue)};
}

ProfileSettings IsoRenderer::profileSettings(const ParameterValues& values) const { return {values.at(kIsovalue)}; }

}  // namespace voxlab

VOXLAB_RENDERERS(iso) { registry.add<voxlab::IsoRenderer>(); }
