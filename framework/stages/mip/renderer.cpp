// voxlab stage mip: renderer "mip": maximum intensity projection.
#include "voxlab/renderers.h"

namespace voxlab {

class MipRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::Largest; }
    std::string id() const override;
    std::string description() const override;
    ProfileModel profileModel() const override { return ProfileModel::Maximum; }
};

std::string MipRenderer::id() const { return "mip"; }

std::string MipRenderer::description() const {
    return "maximum intensity projection: the largest sample along each ray";
}

}  // namespace voxlab

VOXLAB_RENDERERS(mip) { registry.add<voxlab::MipRenderer>(); }
