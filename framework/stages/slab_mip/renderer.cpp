// voxlab stage slab_mip: renderer "slab_mip": thin-slab maximum intensity projection.
#include "voxlab/renderers.h"

#include "voxlab/camera.h"
#include "voxlab/volume.h"

namespace voxlab {

class SlabMipRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::Largest; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    ProfileModel profileModel() const override { return ProfileModel::Maximum; }
};

std::string SlabMipRenderer::id() const { return "slab_mip"; }

std::string SlabMipRenderer::description() const {
    return "thin-slab MIP: MIP of a slab perpendicular to the view, moved by 'offset'";
}

std::vector<ParameterSpec> SlabMipRenderer::parameters() const {
    return {{"offset", ParameterType::Float, -4096.0, 4096.0, 0.0,
             "distance of the slab's centre plane from the volume centre along the view direction, "
             "in units of the smallest voxel spacing"},
            {"thickness", ParameterType::Float, 0.0, 8192.0, 16.0,
             "thickness of the slab, in units of the smallest voxel spacing"}};
}

}  // namespace voxlab

VOXLAB_RENDERERS(slab_mip) { registry.add<voxlab::SlabMipRenderer>(); }
