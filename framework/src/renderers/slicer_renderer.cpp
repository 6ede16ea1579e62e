// voxlab renderer "slicer": one plane through the volume, perpendicular to
// the view, shown in grey (window) or through the transfer function.
#include "voxlab/renderers.h"

namespace voxlab {

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
