// voxlab: the 2D transfer function over (value, gradient magnitude).
//
// A 1D transfer function cannot tell a boundary from the inside of a
// material with the same value. Adding the gradient magnitude g = |grad f|
// as a second axis can (Kindlmann & Durkin 1998; Kniss et al. 2002): the
// boundaries between materials are where g is large.
//
// The function is a list of widgets, each with a colour and an opacity:
//
//  triangle  Levoy's isovalue-contour opacity (M. Levoy, "Display of
//            Surfaces from Volume Data", IEEE CG&A 1988), for a surface of
//            value fv, thickness `radius` r and opacity av:
//               alpha(f, g) = av                            if g = 0 and f = fv
//                           = av (1 - |fv - f| / (r g))     if g > 0 and |fv - f| <= r g
//                           = 0                             otherwise.
//            In the (value, gradient) plane this is a triangle with its apex
//            at (fv, 0) that widens as g grows, so the rendered surface keeps
//            a thickness of about r unit lengths whatever the local gradient.
//  box       constant opacity over value in [v0, v1] and gradient magnitude
//            in [g0, g1].
//
// Several widgets combine as independent layers: opacity
// 1 - prod(1 - alpha_i), colour the opacity-weighted mean of the widgets'
// colours.
//
// Units: values in the data's own units; gradient magnitudes in data units
// per unit length (the smallest voxel spacing), the definition in
// gradients.h, also used for the editor's 2D histogram (histogram2D()).
// Opacities are per unit length, like the 1D transfer function's.
//
// JSON (the scene's section of that name, kTransferFunction2DName, or a file):
//   {"widgets": [
//      {"type": "triangle", "value": 120, "radius": 1.5, "alpha": 0.8, "color": [1, 1, 1]},
//      {"type": "box", "value": [40, 80], "gradient": [0, 5], "alpha": 0.05, "color": [0, 0.6, 0]}
//   ]}
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

namespace voxlab {

// At most this many widgets (the shader keeps them in uniform arrays).
constexpr int kMaxTf2dWidgets = 16;

// The 2D transfer function's short name: the scene's section, the --NAME
// option, the viewer script's command and panel, and the presets' folder of
// a dataset folder (datasets/NAME/). It is its stage's name, spelled once in
// that stage's section.cpp (framework/stages/*/section.cpp), which brings
// the scene section.
extern const char* const kTransferFunction2DName;

struct Tf2dWidget {
    enum class Kind { Triangle, Box };
    Kind kind = Kind::Triangle;
    // Triangle: value = fv (valueRange.x), radius r. Box: valueRange and gradientRange.
    glm::dvec2 valueRange{0.0};
    double radius = 1.0;
    glm::dvec2 gradientRange{0.0};
    glm::vec3 color{1.0f};
    float alpha = 1.0f;

    bool operator==(const Tf2dWidget& o) const;
};

class TransferFunction2D {
public:
    TransferFunction2D() = default;
    explicit TransferFunction2D(std::vector<Tf2dWidget> widgets);  // checks each widget

    const std::vector<Tf2dWidget>& widgets() const { return widgets_; }
    std::vector<Tf2dWidget>& widgets() { return widgets_; }

    // Colour (rgb) and opacity per unit length (a) at value f and gradient
    // magnitude g, by the formulas above. For previews on the CPU.
    glm::vec4 evaluate(double f, double g) const;

    // Errors name the entry and key: "scene.json: KEY.widgets[1].radius: expected a number > 0".
    static TransferFunction2D fromJson(const nlohmann::json& j, const std::string& where,
                                       const std::string& key = "");
    static TransferFunction2D load(const std::string& path);
    nlohmann::json toJson() const;

private:
    std::vector<Tf2dWidget> widgets_;
};

}  // namespace voxlab
