// voxlab: the renderer plug-in interface.
//
// A renderer is a small class that names itself, declares its parameters and
// points at its GLSL entry shader; the RenderEngine does the rest (textures,
// camera uniforms, framebuffer). The entry shader (framework/stages/STAGE/,
// by default STAGE/ID.frag) includes the framework's GLSL libraries and the stage's implementation
// (e.g. "mip/mip.glsl"), which is looked up first in the implementation root:
// reference/ for the reference solution, or a student's submission folder.
//
// Each stage folder registers its renderers (VOXLAB_RENDERERS below); the
// stages are listed once, in framework/stages/stages.cmake, so no linker can
// drop one and the order in `voxlab list` is deliberate.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "voxlab/empty_space.h"
#include "voxlab/gradients.h"
#include "voxlab/scene.h"

namespace voxlab {

class ShaderProgram;
struct Camera;
class TransferFunction;
class Volume;

enum class ParameterType { Float, Int, Bool };

// What a pixel of this renderer's rays holds after each sample, for the ray
// profile (ray_profile.h): the running maximum, minimum or mean, a first hit
// (at `threshold`) or a surface (at `isovalue`), front-to-back compositing,
// or nothing it reads further (the samples' values and pixels only).
enum class ProfileModel { None, Maximum, Minimum, Mean, FirstHit, Isosurface, Composite };

// The value a first hit or an isosurface stops at (data units), and the
// opacity at which compositing stops early (1: it does not).
struct ProfileSettings {
    double threshold = 0.0;
    double earlyTermination = 1.0;
};

// One declared parameter. The command line (--param NAME=VALUE), scene files
// ("parameters": {...}) and the viewer's panels all read these.
//
// A parameter in data units (an isovalue, a threshold) cannot have a fixed
// range: a CT scan and an 8-bit volume differ by orders of magnitude. Such a
// parameter sets `dataUnits`; its min, max and default are then fractions of
// the volume's value range (0 = the smallest value, 1 = the largest), and
// parametersFor() turns them into data units for one volume. A parameter
// that is a difference of data values (a gradient magnitude, in data units
// per unit length) sets `dataSpan` instead: its bounds and default are
// fractions of the range's width (0 = none, 1 = the whole range).
struct ParameterSpec {
    std::string name;
    ParameterType type = ParameterType::Float;
    double minValue = 0.0;
    double maxValue = 1.0;
    double defaultValue = 0.0;
    std::string description;
    bool dataUnits = false;
    bool dataSpan = false;
    bool scaledByData() const { return dataUnits || dataSpan; }
};

const char* parameterTypeName(ParameterType t);

// What an object-order renderer draws with (see Renderer::objectOrder).
// The engine has bound the program and set every uniform, and blends each
// fragment's premultiplied colour over what is already there ("over",
// back to front).
class DrawContext {
public:
    virtual ~DrawContext() = default;
    virtual const Scene& scene() const = 0;
    virtual const Volume& volume() const = 0;
    virtual const Camera& camera() const = 0;
    virtual const ShaderProgram& program() const = 0;
    // Draws triangles (3 world positions each), in order.
    virtual void drawTriangles(const std::vector<glm::vec3>& vertices) = 0;
    // The same, each triangle with its own unit normal for flat shading (the
    // vertex shader's a_face_normal, flat): the same on every GL, where a
    // normal from screen-space derivatives is not at a small triangle's edge.
    virtual void drawFacets(const std::vector<glm::vec3>& vertices) = 0;
    // Draws line segments (2 world positions each).
    virtual void drawLines(const std::vector<glm::vec3>& vertices) = 0;
    // From here on, fragments are kept only where nearer than what is there
    // (the fragment shader writes gl_FragDepth): for opaque geometry in any
    // order (the mesh renderer). The depth buffer starts cleared.
    virtual void enableDepthTest() = 0;
    // Draws one square (two triangles, six vertices: gl_VertexID 0..5) per
    // instance, each instance a vec4 at attribute 0 (a point's world position
    // and value); the vertex shader places the corners.
    virtual void drawInstancedSquares(const std::vector<glm::vec4>& instances) = 0;
    // The transfer function the pass classifies with: the scene's, or the
    // engine's fallback (render_engine.h).
    virtual const TransferFunction& transferFunction() const = 0;

    // Multi-pass drawing (shear-warp's intermediate image): full-screen
    // passes of other fragment shaders, into one of two float RGBA targets
    // (the two have one size: asking one for another size makes both anew,
    // empty), read back as textures, then into the pass's own output.
    // useFullScreenProgram compiles the shader (with voxlab/fullscreen.vert)
    // as the renderer's own is, sets the pass's uniforms, binds it and makes
    // it program(). drawToTarget draws into target 0 or 1 (no blending);
    // drawToOutput goes back to the output, blending "over" again.
    virtual const ShaderProgram& useFullScreenProgram(const std::string& fragmentShader) = 0;
    virtual void drawToTarget(int target, glm::ivec2 size) = 0;
    virtual void clearTarget(glm::vec4 colour) = 0;  // the target drawn to
    virtual void bindTargetTexture(int target, int unit) = 0;
    virtual void drawToOutput() = 0;
    virtual void drawFullScreen() = 0;
    // Binds the volume as a stack of 2D slices perpendicular to `axis` (a
    // 2D array texture, one layer per voxel layer, bilinear within a layer)
    // to texture unit `unit`.
    virtual void bindSliceStack(int axis, int unit) = 0;
};

// A texture that a renderer's entry shader reads and that is itself computed
// on the GPU before the render, by a fragment shader run once per texel (with
// voxlab/fullscreen.vert): the pre-integration table, the light volume. The
// shader sees what the entry shader sees (the scene's uniforms, the transfer
// function, the renderer's parameters, the same baked switches but no
// skipping) plus u_precompute_size (the texture's size) and
// u_precompute_layer (the layer a 3D texture is being computed in: one pass
// per layer), and writes one texel per fragment. The entry shader gets the
// result as sampler `sampler`, linearly filtered and clamped to its edges.
// The engine keeps it until `key`, the volume, the transfer function or the
// shaders change (the renderer puts in `key` whatever else the texture
// depends on: the step, the light direction).
struct Precomputation {
    std::string sampler;         // e.g. "u_preintegration_table"
    std::string fragmentShader;  // on the shader search path
    glm::ivec3 size{1};          // size.z == 1: a 2D texture
    int channels = 4;            // 1 (R32F) or 4 (RGBA32F)
    std::string key;
};

// How a renderer adds the part of a ray inside one brick of a bricked
// volume to what the bricks in front of it left (voxlab/volume_bricks.h,
// shaders/voxlab/bricks.glsl). None: it cannot draw bricks.
enum class BrickCombine { None = 0, Over = 1, FirstHit = 2, Largest = 3, Smallest = 4, Sum = 5 };

class Renderer {
public:
    virtual ~Renderer() = default;
    virtual std::string id() const = 0;
    virtual std::string description() const = 0;
    virtual std::vector<ParameterSpec> parameters() const { return {}; }
    // The parameters for a volume whose values span `dataRange`: data-unit
    // parameters get their range and default in data units.
    std::vector<ParameterSpec> parametersFor(glm::dvec2 dataRange) const;
    // The entry fragment shader, found on the shader search path: by
    // default the stage folder's own, framework/stages/ID/ID.frag.
    virtual std::string fragmentShader() const { return "stages/" + id() + "/" + id() + ".frag"; }
    // How the ray profile reads the pixels of this renderer's rays
    // (voxlab/ray_profile.h), and what it stops at, from the renderer's own
    // parameters (read here, where they are declared).
    virtual ProfileModel profileModel() const { return ProfileModel::None; }
    virtual ProfileSettings profileSettings(const ParameterValues&) const { return {}; }
    // Shaders the renderer makes itself (name -> GLSL text), added to the
    // engine's shader library ahead of the search path: a ray-value stage's
    // entry shader, made from a template (RayValueRenderer).
    virtual std::map<std::string, std::string> generatedShaders() const { return {}; }

    // Image-order renderers (ray casters) run their fragment shader once per
    // pixel over a full-screen triangle. Object-order renderers (texture
    // slicing) instead draw proxy geometry in draw(); their vertex shader is
    // voxlab/world.vert, which places world positions with the camera.
    virtual bool objectOrder() const { return false; }
    virtual std::string vertexShader() const {
        return objectOrder() ? "voxlab/world.vert" : "voxlab/fullscreen.vert";
    }
    virtual void draw(DrawContext& context, const ParameterValues& values) const;
    // Sets the renderer's own uniforms. The default sets each parameter as
    // uniform "u_NAME" (float for Float, int for Int and Bool).
    virtual void setUniforms(const ShaderProgram& program, const ParameterValues& values) const;

    // Whether the renderer classifies samples with the 1D transfer function
    // even when the scene has none (compositing cannot do without one: the
    // engine then supplies a grey ramp over the window, see render_engine.h).
    virtual bool needsTransferFunction() const { return false; }
    // Whether the image depends on the 1D transfer function at all, when the
    // scene has one (the viewer hides the editor otherwise). Most renderers
    // colour by it; an isosurface has a colour of its own, and a renderer classifying
    // by value and gradient has the 2D function instead.
    virtual bool usesTransferFunction() const { return true; }
    // The same for the 2D transfer function (the engine's fallback is one
    // of Levoy's triangles at the middle of the window).
    virtual bool needsTransferFunction2D() const { return false; }
    // The gradient volume to precompute on the CPU and upload, if these
    // parameter values ask for one (see gradients.h): renderers that declare
    // the shared parameters `precomputed_gradients` and `sobel` get it when
    // `precomputed_gradients` is on; others never do.
    std::optional<GradientEstimator> precomputedGradients(const ParameterValues& values) const;
    // The estimator the shader runs at every sample instead; none when the
    // gradients are precomputed.
    std::optional<GradientEstimator> onTheFlyGradients(const ParameterValues& values) const;
    // The textures to compute before drawing (see Precomputation); none by
    // default.
    virtual std::vector<Precomputation> precomputations(const Scene& scene, const Volume& volume,
                                                        const ParameterValues& values) const;
    // Which bricks of the volume these parameter values let the renderer's
    // rays skip (see empty_space.h); the default skips none.
    virtual EmptySpaceRule emptySpaceRule(const ParameterValues& values) const;

    // Whether the scene's other volumes can be drawn with these parameter
    // values: a label map (scene "labels") and a fused second volume
    // ("fusion") need a renderer that classifies with them. Throws
    // voxlab::Error naming the renderer and what it cannot draw; the
    // default draws neither.
    virtual void checkScene(const Scene& scene, const ParameterValues& values) const;

    // How the renderer draws a volume cut into bricks, with these parameter
    // values (BrickCombine). Throws voxlab::Error naming the renderer and
    // the parameter when one of them needs the whole volume at once; the
    // default draws no bricks (None).
    virtual BrickCombine brickCombine(const ParameterValues& values) const;

    // Checks `given` against the declared parameters (unknown name, out of
    // range, not an integer, not a bool) and fills in defaults. Errors name
    // the renderer and parameter: "mip: parameter 'offset' is not declared".
    // Without a data range, data-unit parameters are checked for their name
    // and type only (their defaults are then meaningless).
    ParameterValues resolveParameters(const ParameterValues& given,
                                      std::optional<glm::dvec2> dataRange = std::nullopt) const;
};

// Whether the Bool (or number) parameter `name` is set and not 0 in `values`.
bool parameterOn(const ParameterValues& values, const std::string& name);

class RendererRegistry {
public:
    template <class T, class... Args>
    void add(Args&&... args) {
        renderers_.push_back(std::make_unique<T>(std::forward<Args>(args)...));
    }
    const Renderer* find(const std::string& id) const;
    // Throws voxlab::Error("unknown renderer 'x' (available: a, b, ...)").
    const Renderer& get(const std::string& id) const;
    const std::vector<std::unique_ptr<Renderer>>& all() const { return renderers_; }

private:
    std::vector<std::unique_ptr<Renderer>> renderers_;
};

// A stage folder's renderer.cpp adds its renderers to the registry
// (voxlab/stage_registry.h holds the built-in one):
//   VOXLAB_RENDERERS(my_stage) { registry.add<MyRenderer>(); }
#define VOXLAB_RENDERERS(stage)                                           \
    namespace voxlab {                                                    \
    void stageRenderers_##stage(RendererRegistry& registry);              \
    }                                                                     \
    void voxlab::stageRenderers_##stage(voxlab::RendererRegistry& registry)

}  // namespace voxlab
