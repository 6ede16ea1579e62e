// voxlab: the render engine. It owns the GPU side of a scene (the volume
// texture, the transfer-function table, one compiled program per renderer,
// an offscreen float framebuffer) and runs a renderer's shader over every
// pixel. A current GL context (headless or windowed) is required.
//
// Uniforms every renderer can use (see shaders/voxlab/*.glsl):
//   u_volume, u_volume_dims, u_volume_extent, u_value_scale, u_value_offset,
//   u_min_spacing, u_cam_*, u_pixel_scale, u_image_size, u_orthographic,
//   u_step (world units), u_step_units (in smallest spacings), u_window,
//   u_tf, u_tf_range, u_tf_size, u_has_tf, u_background, u_value_range,
//   u_interpolation, u_roi_min/max, u_clip_plane/point/normal, u_layer,
//   u_gradient_volume, u_bspline_coefficients (the "bspline" interpolation),
//   u_tf2d_*, u_bricks, u_brick_extent, u_brick_count
//   (empty-space skipping, see empty_space.h), and u_PARAM for each declared
//   renderer parameter.
//
// A scene with a cutting plane is drawn in three passes: the scene's
// renderer on the normal's side and the other side's renderer on the other,
// each into a float layer (premultiplied colour and opacity), then the two
// layers laid front over back and over the background
// (shaders/voxlab/cut_compose.frag).
//
// A renderer that needs a transfer function (compositing) and a scene that
// has none get a grey ramp over the window: opacity 0 at its low end to 0.1
// per unit length at its high end. One that needs a 2D transfer function
// gets a single white triangle widget (Levoy's isovalue contour) at the
// middle of the window, radius 1.5, opacity 0.6.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "voxlab/empty_space.h"
#include "voxlab/gl_object.h"
#include "voxlab/image.h"
#include "voxlab/ray_profile.h"
#include "voxlab/renderer.h"
#include "voxlab/scene.h"
#include "voxlab/shader.h"
#include "voxlab/volume.h"

namespace voxlab {

class EngineDrawContext;
class SceneVolumes;
class VolumeTextures;
struct BrickLayout;

// Whether RenderEngine::countSamples() can count a scene's samples: its
// renderer casts rays (slices take no samples along rays) and it has no
// cutting plane (whose two halves are composed into one image).
bool samplesCountable(const RendererRegistry& renderers, const Scene& scene);

// The implementation an engine runs when given none: the project's
// reference/, or the starter code assignments/ in a student release (which
// has no reference/).
std::string defaultImplementationRoot();

class RenderEngine {
public:
    // The engine draws with the renderers of `renderers` (which must outlive
    // it; voxlab/stage_registry.h has the built-in ones), looked up by the
    // scene's renderer id. `implementationRoot` is searched first for stage
    // shaders: the project's reference/ by default, or a student's
    // submission folder.
    explicit RenderEngine(const RendererRegistry& renderers, std::string implementationRoot = "");
    ~RenderEngine();
    RenderEngine(const RenderEngine&) = delete;
    RenderEngine& operator=(const RenderEngine&) = delete;

    // Uploads the volume as a 3D texture in its native precision (R8, R16,
    // R32F; int16 is shifted by +32768 into R16 so that no value is lost).
    // The engine keeps the volume's address (for its value range, the
    // empty-space bricks and volume()), so the volume must outlive the engine
    // or the next setVolume(). A temporary would be destroyed at the end of
    // the call and leave a dangling pointer, so rvalues are refused at
    // compile time (the overload below; `const Volume&&` catches const and
    // non-const rvalues alike, as std::ref does).
    void setVolume(const Volume& volume);
    void setVolume(const Volume&& volume) = delete;
    const Volume* volume() const { return volume_; }

    // Renders `scene` (its dataset is ignored: the volume set above is used)
    // and returns the float image.
    Image render(const Scene& scene);
    // The same into a caller's framebuffer, at the scene's size, with the
    // viewport at the framebuffer's origin.
    void renderTo(const Scene& scene, unsigned framebuffer);
    // Renders into the engine's own float framebuffer and leaves it there
    // (the viewer blits it); offscreenFramebuffer() names it.
    void renderOffscreen(const Scene& scene);
    unsigned offscreenFramebuffer() const { return target_.framebuffer; }
    Image readBack() const;
    // A tile of the image (x, y, width, height in framebuffer pixels, y up):
    // the next renders shade only these pixels and leave the others as they
    // were, where the scene allows it (a ray caster drawn in one pass: no
    // cutting plane, no bricks, not object order); lastRenderTiled() says
    // whether the last render did. The viewer renders a large image a band
    // at a time, between frames of its UI. std::nullopt: the whole image.
    void setTile(std::optional<glm::ivec4> tile) { tile_ = tile; }
    bool lastRenderTiled() const { return tiled_; }
    // The width in pixels of the lines renderers draw (texture slicing's and
    // the mesh's wireframes): the viewer's UI scale. Where the context cannot
    // draw wide lines (a forward-compatible core context) they stay 1 wide.
    void setLineWidth(float pixels) { lineWidth_ = pixels; }

    // Forgets compiled programs so that the next render re-reads the GLSL.
    // A program that then fails to compile is replaced by its last good
    // version (live reload keeps rendering), and shaderError() holds the
    // compiler's message until the next reload; a program that never
    // compiled throws ShaderError as usual.
    void reloadShaders();
    const std::string& shaderError() const { return shaderError_; }
    // Every shader file the current programs were built from (to watch for
    // edits), as paths that work from any working folder.
    std::vector<std::string> shaderSources() const;
    // The shader files of the renderer's program in the last render (the
    // viewer names the stubs that render reached).
    const std::vector<std::string>& lastRenderSources() const { return lastRenderSources_; }
    // The starter code's stubs compiled into the last render's programs,
    // "stage/function" (ShaderProgram::stubs), whether or not a pixel ran one.
    const std::vector<std::string>& lastRenderStubs() const { return lastRenderStubs_; }
    // The stubs whose code ran for some pixel of `scene`: it is drawn again,
    // into a target of the engine's own (the image stays where it was), with
    // every pixel writing the set of the program's numbered stubs it reached
    // (u_report_stubs, voxlab/not_implemented.glsl); with `maxSide`, at most
    // that many pixels a side. A scene drawn in several passes (object
    // order, a cutting plane, bricks) cannot say per pixel: for it, every
    // stub compiled in.
    std::vector<std::string> stubsReached(const Scene& scene, int maxSide = 0);
    // The colour texture of the offscreen framebuffer (RGBA32F), for
    // compositing two engines' images (the viewer's split view).
    unsigned offscreenTexture() const { return target_.color; }
    const std::string& implementationRoot() const { return implementationRoot_; }
    const RendererRegistry& renderers() const { return renderers_; }

    // The samples `scene` takes in all, summed over its pixels: the scene is
    // rendered once with every sample_position() counted (see
    // shaders/voxlab/sample_counter.glsl), with skipping and early
    // termination as the scene has them. Only for scenes samplesCountable()
    // accepts (voxlab::Error otherwise); the image in the offscreen target
    // is the counts.
    double countSamples(const Scene& scene);
    // The ray profile of pixel (px, py) of `scene` (py counted downwards),
    // taken from this engine's own shaders, the stages of its
    // implementation included (voxlab/ray_profile.h, voxlab/profile.glsl).
    // Throws voxlab::Error for a pixel outside the image; a renderer that
    // draws slices, or a volume drawn in bricks, gives a profile that says
    // so in `why`. The offscreen image is not touched.
    RayProfile profileRay(const Scene& scene, int px, int py);
    // Normally whether samples are counted is baked into the program, so a
    // count compiles a program of its own. With this on, u_count_samples
    // stays a uniform in unbricked renders: countSamples() after render()
    // of the same scene draws with the program and llvmpipe variant the
    // render compiled, at the price of one test of the uniform per sample.
    // The grader's runaway-loop check uses it: on llvmpipe a compile costs
    // more than a 128x128 render. The images are the same either way.
    void setCountingByUniform(bool on) { countingByUniform_ = on; }
    // Fewer compiles at a small cost in speed (ShaderLibrary::setCompileOnce):
    // for the grading worker and the tests, which draw each program a few times.
    void setCompileOnce(bool on) { library_.setCompileOnce(on); }
    // Linear filtering written out in float (voxlab/filtering.glsl) in every
    // program compiled from now on: the grader's choice, so that a verdict
    // does not depend on the GL's filtering precision. Set before rendering.
    void setExactFiltering(bool on) { library_.setGlobalConstant("u_exact_filtering", on ? 1 : 0); }

    // Bricked rendering (voxlab/volume_bricks.h): the GPU memory the volume's
    // textures may take unless a scene says otherwise ("gpu_memory"): what
    // the driver reports (NVIDIA's and AMD's extensions), else a quarter of
    // the machine's memory for a software renderer, else 1 GiB.
    std::size_t defaultGpuMemoryBudget() const { return defaultBudget_; }
    // The layout of the last render's volume textures (one brick unbricked),
    // and the bricks uploaded since the engine began (all volumes, all budgets).
    // The bricks' passes drawn and the bytes uploaded, counted the same
    // way. A brick whose pass could change no pixel (out of view, or empty
    // for the classification with skipping on) is neither drawn nor
    // uploaded.
    const BrickLayout& brickLayout() const;
    std::size_t brickUploads() const;
    std::size_t brickBytesUploaded() const;
    std::size_t bricksDrawn() const { return bricksDrawn_; }

private:
    // One transfer-function table on the GPU and what it was baked from.
    struct TransferFunctionSlot {
        GlTexture texture;
        TransferFunctionTable table;
        std::vector<ControlPoint> points;
        glm::dvec2 range{0.0};
        unsigned long generation = 0;  // counts the bakes (precomputed textures depend on it)
    };
    // What differs between the passes of a cutting-plane view.
    struct Pass {
        const Renderer* renderer = nullptr;
        ParameterValues values;
        const TransferFunction* transferFunction = nullptr;
        int slot = 0;             // which TransferFunctionSlot
        bool layer = false;       // premultiplied output, no background
        bool clip = false;        // keep dot(p - clipPoint, clipNormal) >= 0
        glm::vec3 clipPoint{0.0f}, clipNormal{0.0f};
    };

    // What every program of a pass reads besides the scene (draw()).
    struct PassInputs {
        const TransferFunction* tf = nullptr;  // the scene's or the fallback
        std::vector<Tf2dWidget> widgets;
    };
    // A texture made by a Precomputation, and what it was made from.
    struct PrecomputedTexture {
        GlTexture texture;
        glm::ivec3 size{0};
        int channels = 0;
        std::string key;
    };

    // The program for these shaders with these baked constants (cached).
    const ShaderProgram& program(const std::string& vertexShader, const std::string& fragmentShader,
                                 const ShaderConstants& constants);
    friend class EngineDrawContext;
    unsigned sliceStack(int axis);
    void setSceneUniforms(const ShaderProgram& prog, const Scene& scene) const;
    void draw(const Scene& scene, const Pass& pass);
    // The parts of draw() (render_engine.cpp).
    PassInputs passInputs(const Scene& scene, const Pass& pass, std::optional<TransferFunction>& fallback) const;
    void bindTables(const Scene& scene, const Pass& pass, const PassInputs& inputs);
    void drawObjectOrder(const Scene& scene, const Pass& pass, const PassInputs& inputs, const ShaderProgram& prog,
                         const ShaderConstants& constants);
    void drawFullScreen(const Pass& pass, const ShaderProgram& prog);
    ShaderConstants switchesFor(const Scene& scene, const Pass& pass, const PassInputs& inputs, bool skipping,
                                BrickCombine combine) const;
    void setPassUniforms(const ShaderProgram& prog, const Scene& scene, const Pass& pass, const PassInputs& inputs);
    // Precomputed textures (render_engine_precompute.cpp): computes the
    // `index`th of the pass's textures unless it is still up to date, and
    // binds them all for the entry shader.
    void runPrecomputation(const Precomputation& what, int index, const Scene& scene, const Pass& pass,
                           const PassInputs& inputs, const ShaderConstants& constants);
    void bindPrecomputations(const ShaderProgram& prog, const std::vector<Precomputation>& what, int slot);
    void drawCut(const Scene& scene, unsigned framebuffer);
    void uploadTransferFunction(TransferFunctionSlot& slot, const TransferFunction& tf);
    void uploadGradients(GradientEstimator estimator);
    void uploadBsplineCoefficients();  // once per volume, for the "bspline" interpolation
    void ensureTarget(int width, int height);
    void ensureLayers(int width, int height);
    // Adds a program's files to lastRenderSources_ (every program a render used).
    void noteSources(const ShaderProgram& prog);
    // The two float targets of multi-pass object-order renderers (shear-warp),
    // both of one size.
    void ensureIntermediate(int target, glm::ivec2 size);
    // Empty-space skipping (render_engine_bricks.cpp): builds the brick grid
    // once per volume, marks the bricks `rule` lets rays skip, and binds the
    // result for the shaders.
    void bindBricks(const ShaderProgram& prog, const EmptySpaceRule& rule, const TransferFunctionTable* table,
                    const std::vector<Tf2dWidget>& widgets);
    // render_engine_bricked.cpp
    std::size_t budgetFor(const Scene& scene) const;
    BrickCombine checkBricked(const Scene& scene, const Pass& pass) const;
    void bindVolumeBrick(int brick, const ShaderProgram& prog, const Scene& scene);
    bool brickNeeded(int brick, const Camera& cam, bool skipping) const;
    void drawBricked(const Scene& scene, const Pass& pass, const PassInputs& inputs, const ShaderProgram& prog,
                     const ShaderConstants& constants, BrickCombine combine,
                     const std::function<void(const ShaderProgram&)>& prepare);

    const RendererRegistry& renderers_;
    std::string implementationRoot_;
    ShaderLibrary library_;
    const Volume* volume_ = nullptr;
    std::unique_ptr<VolumeTextures> volumeTextures_;
    std::size_t defaultBudget_ = 0;
    int maxTextureSize_ = 0;
    GlVertexArray vao_;
    FloatTarget target_;  // the image
    int fboWidth_ = 0, fboHeight_ = 0;
    std::optional<glm::ivec4> tile_;
    bool tiled_ = false;
    float lineWidth_ = 1.0f;
    // Two layers (or a bricked render's state, taking turns) and a bricked
    // render's sample counts.
    FloatTarget layers_[3];
    FloatTarget intermediate_[2];
    glm::ivec2 intermediateSize_{0};  // both targets
    int layerWidth_ = 0, layerHeight_ = 0;
    float valueScale_ = 1.0f, valueOffset_ = 0.0f;
    std::map<std::string, std::unique_ptr<ShaderProgram>> programs_;
    std::vector<std::string> lastRenderSources_;
    std::vector<std::string> lastRenderStubs_;
    std::vector<std::string> mainProgramStubs_;  // the numbered stubs of the last single-pass draw's program
    bool reportingStubs_ = false;
    int programsNoted_ = 0;
    FloatTarget stubTarget_;
    int stubWidth_ = 0, stubHeight_ = 0;
    std::map<std::string, std::unique_ptr<ShaderProgram>> previousPrograms_;  // before the last reload
    std::string shaderError_;
    TransferFunctionSlot tf_[2];  // the scene's, and the cutting plane's other side
    // The gradient volume on the GPU: for which volume (by upload count) and estimator.
    GlTexture gradientTexture_;
    std::optional<GradientEstimator> gradientEstimator_;
    unsigned long volumeGeneration_ = 0, gradientGeneration_ = 0;
    GlTexture bsplineTexture_;
    unsigned long bsplineGeneration_ = 0;
    // Object-order drawing: a vertex buffer for proxy geometry, and the
    // volume as three stacks of 2D slices (built on first use per volume).
    GlVertexArray geometryVao_;
    GlBuffer geometryVbo_, geometryNormalVbo_;
    GlVertexArray pointVao_;
    GlBuffer pointVbo_;  // instanced squares (splats): a position and a value each
    GlTexture sliceStacks_[3];
    unsigned long sliceStackGeneration_[3] = {0, 0, 0};
    // Empty-space skipping: the grid, the volume it belongs to, and its
    // texture (min, max, visible, 0 per brick) as last uploaded.
    // Empty-space skipping's grids (bindBricks): one of kBrickSize voxels a
    // side, and the 2D transfer function's finer one (skippingBrickSize),
    // each built on first use per volume, with its flags and their texture;
    // `skipping_` is the one the last pass bound.
    struct SkipGrid {
        std::unique_ptr<BrickGrid> grid;
        unsigned long generation = 0;
        GlTexture texture;
        std::vector<glm::vec4> texels;  // (smallest, largest, visible, 0) per brick
    };
    SkipGrid skipGrids_[2];
    const SkipGrid* skipping_ = nullptr;
    std::size_t bricksDrawn_ = 0;  // bricked passes (bricksDrawn())
    // The ray profile's instrumented passes (render_engine_profile.cpp):
    // which one is being drawn (0: none), of which pixel, and its target.
    int profilePass_ = 0;
    glm::vec2 profilePixel_{0.0f};
    int profileWidth_ = 1, profileFirst_ = 0;
    FloatTarget profileTarget_;
    glm::ivec2 profileTargetSize_{0};
    // The scene's own renderer as a pass: with a cutting plane, clipped to
    // the half-space the plane's normal points into (drawCut's first layer).
    Pass scenePass(const Scene& scene) const;
    std::vector<glm::vec4> drawProfilePass(const Scene& scene, const Pass& pass, int which, int first, int count);
    bool countingSamples_ = false;
    bool countingByUniform_ = false;
    // Precomputed textures, per transfer-function slot (the two sides of a
    // cutting plane) and index, and their framebuffer.
    std::map<std::pair<int, int>, PrecomputedTexture> precomputed_;
    GlFramebuffer precomputeFbo_;
    unsigned long shaderGeneration_ = 0;
    // The scene's label map and second volume (scene_volumes.h).
    std::unique_ptr<SceneVolumes> sceneVolumes_;
};

}  // namespace voxlab
