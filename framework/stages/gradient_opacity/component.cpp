// voxlab stage gradient_opacity: boundary emphasis as a compositing
// component (voxlab/renderers.h): opacity times a ramp of the gradient
// magnitude, gradient_opacity_weight() in the stage's GLSL.
#include "voxlab/renderers.h"

namespace voxlab {
namespace {

class GradientOpacityComponent final : public CompositeComponent {
public:
    // The bounds are gradient magnitudes, data units per unit length, given
    // here as fractions of the value range's width (dataSpan).
    Phase phase() const override { return Phase::Classified; }
    std::vector<ParameterSpec> parameters() const override {
        ParameterSpec low{"gradient_low", ParameterType::Float, 0.0, 0.5, 0.01,
                          "gradient opacity: at or below this gradient magnitude, no opacity (data units per unit "
                          "length)"};
        ParameterSpec high{"gradient_high", ParameterType::Float, 0.0, 0.5, 0.08,
                           "gradient opacity: at or above this gradient magnitude, full opacity (data units per unit "
                           "length)"};
        low.dataSpan = high.dataSpan = true;
        return {{"gradient_opacity", ParameterType::Bool, 0, 1, 0,
                 "multiply opacity by a ramp of the gradient magnitude: homogeneous regions fade, boundaries stay"},
                low,
                high};
    }
};

}  // namespace
}  // namespace voxlab

VOXLAB_COMPOSITE_COMPONENTS(gradient_opacity) { components.add<voxlab::GradientOpacityComponent>(); }
