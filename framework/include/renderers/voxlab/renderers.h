// voxlab: what several stages' renderers share: the renderer of ray-value
// stages, the shading and compositing parameters, the texture slicers'
// polygons. Each renderer is declared and defined in its stage's folder,
// framework/stages/STAGE/renderer.cpp, beside its shaders.
#pragma once

#include <memory>
#include <mutex>

#include "voxlab/renderer.h"

namespace voxlab {

// What the ray profile stops at for compositing (shared_parameters.cpp),
// from compositingParameters().
ProfileSettings compositingProfileSettings(const ParameterValues& values);

// The renderer of a ray-value stage: a stage whose function
// `float <stage>_ray(Ray ray)` (in <stage>/<stage>.glsl) returns one value
// per ray in data units, shown through the window or the transfer function
// (MinIP, the mean, ...). Its entry shader is made from
// shaders/renderers/ray_value.frag.in with the stage's name filled in, and
// its parameters become uniforms u_NAME; so adding such a stage takes its
// folders and framework/stages/STAGE/renderer.cpp, e.g.
//   VOXLAB_RENDERERS(my_stage) {
//       registry.add<RayValueRenderer>("my_stage", "what it shows: ...", ProfileModel::Minimum);
//   }
// What a ray-value stage's function returns: one value, in data units,
// shown through the window or the transfer function (float STAGE_ray(Ray));
// or a colour, premultiplied, with its opacity (vec4 STAGE_ray(Ray)), which
// classifies with the transfer function (a grey ramp when the scene has
// none).
enum class RayResult { Value, Colour };

class RayValueRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues& values) const override;
    RayValueRenderer(std::string stage, std::string description, ProfileModel profile = ProfileModel::None,
                     std::vector<ParameterSpec> parameters = {}, RayResult result = RayResult::Value);
    bool needsTransferFunction() const override { return result_ == RayResult::Colour; }
    std::string id() const override { return stage_; }
    std::string description() const override { return description_; }
    std::vector<ParameterSpec> parameters() const override { return parameters_; }
    ProfileModel profileModel() const override { return profile_; }
    std::map<std::string, std::string> generatedShaders() const override;

private:
    std::string stage_, description_;
    ProfileModel profile_;
    std::vector<ParameterSpec> parameters_;
    RayResult result_;
};

// A feature that compositing switches on per scene (boundary emphasis,
// occlusion, pre-integration, shadowing, ...), brought by its own stage's
// folder as Inviwo's shader components are: its parameters, the first of
// them a Bool that switches it on (the entry shader reads each as u_NAME and
// calls the stage's GLSL under the switch); the texture it needs computed
// before a frame; whether it reads beyond one brick of a bricked volume;
// whether empty-space skipping keeps its image; whether it classifies the
// samples itself (then it does not combine with a label map or a fused
// volume, which classify them). A stage adds its component in its
// framework/stages/STAGE/component.cpp:
//   VOXLAB_COMPOSITE_COMPONENTS(my_feature) { components.add<MyFeatureComponent>(); }
// and its GLSL in framework/stages/STAGE/component.glsl: its uniforms (but
// the switch) and vec4 STAGE_component(vec4 c, vec3 p, Ray ray), which the
// entry shader calls, where the switch is on, at the component's phase:
// in place of the classification, on the classified sample, or on the lit
// one (the generated components.glsl, compositeComponentsGlsl() of
// voxlab/stage_registry.h).
class CompositeComponent {
public:
    enum class Phase { Classify, Classified, Lit };
    virtual ~CompositeComponent() = default;
    virtual std::vector<ParameterSpec> parameters() const = 0;
    virtual Phase phase() const = 0;
    virtual bool readsBeyondBrick() const { return false; }
    virtual bool keepsSkipping() const { return true; }
    virtual bool classifies() const { return false; }
    virtual std::vector<Precomputation> precomputations(const Scene&, const Volume&, const ParameterValues&) const {
        return {};
    }
    // Its switch, the first parameter's name, and whether `values` turn it on.
    std::string switchName() const { return parameters().front().name; }
    bool on(const ParameterValues& values) const { return parameterOn(values, switchName()); }
};

class CompositeComponents {
public:
    template <class T>
    void add() {
        components_.push_back(std::make_unique<T>());
        stages_.push_back(stage_);
    }
    const std::vector<std::unique_ptr<CompositeComponent>>& all() const { return components_; }
    // The stage whose folder brought the i-th component (its GLSL's prefix).
    const std::string& stage(std::size_t i) const { return stages_.at(i); }
    void setStage(std::string stage) { stage_ = std::move(stage); }  // while its folder adds

private:
    std::vector<std::unique_ptr<CompositeComponent>> components_;
    std::vector<std::string> stages_;
    std::string stage_;
};

#define VOXLAB_COMPOSITE_COMPONENTS(stage)                                \
    namespace voxlab {                                                    \
    void stageComponents_##stage(CompositeComponents& components);        \
    }                                                                     \
    void voxlab::stageComponents_##stage(voxlab::CompositeComponents& components)

// Parameters several renderers declare alike (shared_parameters.cpp).
// Shading: shading, blinn, ka, kd, ks, shininess, light_azimuth,
// light_elevation, min_gradient, and the gradient's sobel and
// precomputed_gradients (see shaders/voxlab/lighting.glsl, gradients.glsl).
std::vector<ParameterSpec> shadingParameters(bool shadingByDefault);
// Compositing: early_termination, back_to_front, jitter (what the ray
// profile stops at, read from them, is declared at the top).
std::vector<ParameterSpec> compositingParameters();
// Draws the texture slicers' convex polygons in the order given (back to
// front), and, when `outline` is set, the outlines of every n-th polygon on
// top: n keeps about kOutlinedSlices outlines whatever the step, since at
// the default step (hundreds of polygons) outlining all of them paints a
// solid box and hides the structure the wireframe is there to show.
constexpr int kOutlinedSlices = 24;
void drawSlicePolygons(DrawContext& ctx, const std::vector<std::vector<glm::dvec3>>& polygons, bool outline);
int outlineStride(std::size_t polygons);  // n for that many polygons (>= 1)

}  // namespace voxlab
