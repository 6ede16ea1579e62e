// voxlab stage slicer: renderer "slicer": one plane through the volume, perpendicular to
// the view, shown in grey (window) or through the transfer function.
#include "voxlab/renderers.h"

namespace voxlab {

class SlicerRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::FirstHit; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
};

std::string SlicerRenderer::id() const { return "slicer"; }

std::string SlicerRenderer::description() const {
    return "a plane through the volume centre, perpendicular to the view (moved by 'offset')";
}

std::vector<ParameterSpec> SlicerRenderer::parameters() const {
    return {{"offset", ParameterType::Float, -4096.0, 4096.0, 0.0,
             "distance of the plane from the volume centre along the view direction, "
             "in units of the smallest voxel spacing"},
            {"gradient", ParameterType::Bool, 0, 1, 0,
             "show the gradient magnitude (data units per unit length, through the window) instead of the value"},
            {"sobel", ParameterType::Bool, 0, 1, 0, "26-neighbour (Sobel-like) gradient instead of central differences"},
            {"precomputed_gradients", ParameterType::Bool, 0, 1, 0,
             "read gradients from a volume computed on the CPU instead of estimating them"}};
}

}  // namespace voxlab

VOXLAB_RENDERERS(slicer) { registry.add<voxlab::SlicerRenderer>(); }
