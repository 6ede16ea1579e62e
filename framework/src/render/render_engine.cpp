// voxlab: the render engine (see render_engine.h).
#include "voxlab/render_engine.h"

#include <algorithm>
#include <filesystem>

#include "voxlab/bspline.h"
#include "voxlab/error.h"
#include "voxlab/stub_text.h"
#include "voxlab/scene_volumes.h"
#include "engine_draw_context.h"
#include "engine_internal.h"
#include "volume_textures.h"
#include "voxlab_gl.h"
#ifdef __EMSCRIPTEN__
#include <emscripten/html5.h>
#endif

namespace voxlab {
namespace {

// The browser build keeps 16-bit and float volumes in R32F textures
// (scene_volumes.cpp), which WebGL 2 filters only with the extension
// OES_texture_float_linear: without it "hardware" interpolation would read
// zeros, a black image. Said in one line instead. Natively: always fine.
void checkHardwareFiltering(const Scene& scene, const Volume& volume) {
#ifdef __EMSCRIPTEN__
    static const bool floatLinear =
        emscripten_webgl_enable_extension(emscripten_webgl_get_current_context(), "OES_texture_float_linear");
    if (scene.interpolation == Interpolation::Hardware && volume.type() != VoxelType::UInt8 && !floatLinear)
        throw Error("this browser's WebGL cannot filter 16-bit or float volumes (no OES_texture_float_linear): "
                    "choose the trilinear interpolation, or use the native voxlab");
#else
    (void)scene, (void)volume;
#endif
}

TransferFunction2D fallbackTransferFunction2D(glm::dvec2 window) {
    Tf2dWidget w;
    w.kind = Tf2dWidget::Kind::Triangle;
    w.valueRange = glm::dvec2(0.5 * (window.x + window.y));
    w.radius = 1.5;
    w.alpha = 0.6f;
    return TransferFunction2D({w});
}

}  // namespace

namespace {

// A mistyped implementation folder must not quietly render the reference.
std::string checkedImplementationRoot(const std::string& root) {
    if (root.empty()) return defaultImplementationRoot();
    if (!std::filesystem::is_directory(root))
        throw Error("implementation root '" + root + "' is not a folder");
    return root;
}

}  // namespace

std::string defaultImplementationRoot() {
    // A student release has no reference/: the starter code is the default.
    return projectRoot() + (std::filesystem::is_directory(projectRoot() + "/reference") ? "/reference" : "/assignments");
}

RenderEngine::RenderEngine(const RendererRegistry& renderers, std::string implementationRoot)
    : renderers_(renderers),
      implementationRoot_(checkedImplementationRoot(implementationRoot)),
      library_(ShaderLibrary::forImplementation(implementationRoot_)) {
    // Entry shaders the renderers make themselves (ray-value stages).
    for (const auto& renderer : renderers_.all())
        for (const auto& [name, text] : renderer->generatedShaders()) library_.addGenerated(name, text);
    vao_ = GlVertexArray::make();  // core profile: drawing needs a bound VAO
    volumeTextures_ = std::make_unique<VolumeTextures>(softwareRenderer());
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxTextureSize_);
    defaultBudget_ = driverGpuMemoryBudget();
    gradientTexture_ = GlTexture::make();
    bsplineTexture_ = GlTexture::make();
    for (TransferFunctionSlot& slot : tf_) slot.texture = GlTexture::make();
    sceneVolumes_ = std::make_unique<SceneVolumes>();
    checkGlError("creating the render engine");
}

// The GL objects go with their owners (gl_object.h), after the programs
// and the textures that hold volumes.
RenderEngine::~RenderEngine() {
    programs_.clear();
    sceneVolumes_.reset();
    volumeTextures_.reset();
}

// A volume beyond one texture's size or the budget is cut into bricks
// (volume_bricks.h); the textures are made for the default budget now, and
// again at the first render whose scene sets another ("gpu_memory").
void RenderEngine::setVolume(const Volume& volume) {
    ++volumeGeneration_;
    volumeTextures_->set(volume, volumeGeneration_, defaultBudget_, maxTextureSize_);
    const glm::vec2 scaleOffset = volumeTextures_->scaleOffset();
    valueScale_ = scaleOffset.x, valueOffset_ = scaleOffset.y;
    volume_ = &volume;
    for (TransferFunctionSlot& slot : tf_) slot.table.size = 0;  // the value range may differ
}

void RenderEngine::uploadTransferFunction(TransferFunctionSlot& slot, const TransferFunction& tf) {
    const glm::dvec2 range = volume_->valueRange();
    if (slot.table.size > 0 && tf.points() == slot.points && range == slot.range) return;  // still right
    // The table spans the data's value range; bake() sizes it so that linear
    // interpolation stays within half a grey level of the exact function.
    slot.table = tf.bake(range.x, range.y);
    // Row-major in a 2D texture (see transfer_function.h); the shader
    // fetches and interpolates entries itself, so no filtering here.
    uploadTableTexture(slot.texture, slot.table);
    slot.points = tf.points();
    slot.range = range;
    ++slot.generation;
}

void RenderEngine::uploadGradients(GradientEstimator estimator) {
    if (gradientGeneration_ == volumeGeneration_ && gradientEstimator_ == estimator) return;
    const std::vector<glm::vec3> gradients = computeGradients(*volume_, estimator);
    const glm::ivec3 d = volume_->dims();
    glBindTexture(GL_TEXTURE_3D, gradientTexture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage3D(GL_TEXTURE_3D, 0, GL_RGB32F, d.x, d.y, d.z, 0, GL_RGB, GL_FLOAT, gradients.data());
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
    checkGlError("uploading the gradient volume");
    gradientEstimator_ = estimator;
    gradientGeneration_ = volumeGeneration_;
}

void RenderEngine::uploadBsplineCoefficients() {
    if (bsplineGeneration_ == volumeGeneration_) return;
    const std::vector<float> coefficients = bsplineCoefficients(*volume_);
    const glm::ivec3 d = volume_->dims();
    glBindTexture(GL_TEXTURE_3D, bsplineTexture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, d.x, d.y, d.z, 0, GL_RED, GL_FLOAT, coefficients.data());
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // read with texelFetch
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGlError("uploading the B-spline coefficients");
    bsplineGeneration_ = volumeGeneration_;
}

const ShaderProgram& RenderEngine::program(const std::string& vertexShader, const std::string& fragmentShader,
                                           const ShaderConstants& constants) {
    std::string key = vertexShader + " " + fragmentShader;
    for (const auto& [name, value] : constants) key += " " + name + "=" + std::to_string(value);
    auto it = programs_.find(key);
    if (it != programs_.end()) return *it->second;
    std::unique_ptr<ShaderProgram> compiled;
    try {
        compiled = std::make_unique<ShaderProgram>(library_, vertexShader, fragmentShader, constants);
    } catch (const ShaderError& e) {
        // Live reload: an edit that breaks the shader keeps the last good
        // program running and says why.
        auto previous = previousPrograms_.find(key);
        if (previous == previousPrograms_.end()) throw;
        shaderError_ = e.what();
        compiled = std::move(previous->second);
        previousPrograms_.erase(previous);
    }
    return *programs_.emplace(key, std::move(compiled)).first->second;
}

void RenderEngine::reloadShaders() {
    for (auto& [key, prog] : programs_) previousPrograms_[key] = std::move(prog);
    programs_.clear();
    shaderError_.clear();
    ++shaderGeneration_;  // precomputed textures are made again
}

namespace {

// A program's files are named for messages: relative to the project's root
// when inside it. Watching them needs paths that work from any folder.
std::string filePath(const std::string& shown) {
    return std::filesystem::path(shown).is_absolute() ? shown : projectRoot() + "/" + shown;
}

}  // namespace

std::vector<std::string> RenderEngine::shaderSources() const {
    std::vector<std::string> files;
    for (const auto* programs : {&programs_, &previousPrograms_})
        for (const auto& [key, prog] : *programs)
            for (const std::string& shown : prog->sourceFiles()) {
                const std::string f = filePath(shown);
                if (std::find(files.begin(), files.end(), f) == files.end()) files.push_back(f);
            }
    return files;
}

void RenderEngine::noteSources(const ShaderProgram& prog) {
    ++programsNoted_;
    for (const std::string& stub : prog.stubs())
        if (std::find(lastRenderStubs_.begin(), lastRenderStubs_.end(), stub) == lastRenderStubs_.end())
            lastRenderStubs_.push_back(stub);
    for (const std::string& shown : prog.sourceFiles()) {
        const std::string f = filePath(shown);
        if (std::find(lastRenderSources_.begin(), lastRenderSources_.end(), f) == lastRenderSources_.end())
            lastRenderSources_.push_back(f);
    }
}

void RenderEngine::ensureTarget(int width, int height) {
    if (target_.made() && width == fboWidth_ && height == fboHeight_) return;
    target_.make(width, height);
    fboWidth_ = width, fboHeight_ = height;
}

// Both targets are made anew together when the size changes
// (FloatTarget::makeTogether: a target remade alone could take the other's
// freed storage, and softpipe then sampled that one's tiles).
void RenderEngine::ensureIntermediate(int target, glm::ivec2 size) {
    if (intermediate_[target].made() && intermediateSize_ == size) return;
    FloatTarget::makeTogether(intermediate_, 2, size.x, size.y);
    for (const FloatTarget& t : intermediate_) {
        // Read back with bilinear filtering (the warp), clamped to transparent edges by the reader.
        glBindTexture(GL_TEXTURE_2D, t.color);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    intermediateSize_ = size;
}

void RenderEngine::ensureLayers(int width, int height) {
    if (layers_[0].made() && width == layerWidth_ && height == layerHeight_) return;
    FloatTarget::makeTogether(layers_, 3, width, height);  // they take turns as each other's input
    layerWidth_ = width, layerHeight_ = height;
}

// Uniforms that depend on the scene and the volume only: the volume, the
// camera, sampling, the region of interest.
void RenderEngine::setSceneUniforms(const ShaderProgram& prog, const Scene& scene) const {
    const Volume& vol = *volume_;
    prog.set("u_volume", kVolumeUnit);
    prog.set("u_volume_dims", vol.dims());
    prog.set("u_volume_extent", glm::vec3(vol.extent()));
    prog.set("u_value_scale", valueScale_);
    prog.set("u_value_offset", valueOffset_);
    prog.set("u_value_range", glm::vec2(vol.valueRange()));
    prog.set("u_min_spacing", float(vol.minSpacing()));
    prog.set("u_interpolation", int(scene.interpolation));

    const Camera cam = Camera::make(scene.camera, vol.extent(), scene.width, scene.height);
    prog.set("u_cam_position", glm::vec3(cam.position));
    prog.set("u_cam_forward", glm::vec3(cam.forward));
    prog.set("u_cam_right", glm::vec3(cam.right));
    prog.set("u_cam_down", glm::vec3(cam.down));
    prog.set("u_pixel_scale", float(cam.pixelScale));
    prog.set("u_image_size", glm::vec2(scene.width, scene.height));
    prog.set("u_orthographic", cam.projection == Projection::Orthographic ? 1 : 0);
    if (profilePass_ != 0) {  // the ray profile's run (render_engine_profile.cpp)
        prog.set("u_profile_pixel", profilePixel_);
        prog.set("u_profile_width", profileWidth_);
        prog.set("u_profile_first", profileFirst_);
    }

    prog.set("u_step", float(scene.step * vol.minSpacing()));
    prog.set("u_step_units", float(scene.step));
    const glm::dvec2 window = scene.window.value_or(vol.valueRange());
    prog.set("u_window", glm::vec2(window));
    prog.set("u_background", scene.background);

    // The region of interest, in world units, never larger than the box.
    glm::dvec3 lo(0.0), hi = vol.extent();
    if (scene.roi) {
        lo = glm::max(lo, scene.roi->min * vol.spacing());
        hi = glm::min(hi, scene.roi->max * vol.spacing());
        // A region that misses the box is empty. An inverted slab (lo > hi)
        // would still clip rays along that axis to an interval outside the
        // box, so use a single point outside it: no ray enters a point.
        if (lo.x >= hi.x || lo.y >= hi.y || lo.z >= hi.z) lo = hi = glm::dvec3(-1.0);
    }
    prog.set("u_roi_min", glm::vec3(lo));
    prog.set("u_roi_max", glm::vec3(hi));
    // Clip planes: points from voxel to world coordinates; their count is
    // baked into the program (draw()).
    for (std::size_t i = 0; i < scene.clipPlanes.size(); ++i) {
        const std::string index = "[" + std::to_string(i) + "]";
        prog.set(("u_clip_plane_points" + index).c_str(), glm::vec3(scene.clipPlanes[i].point * vol.spacing()));
        prog.set(("u_clip_plane_normals" + index).c_str(), glm::vec3(glm::normalize(scene.clipPlanes[i].normal)));
    }
}

// The uniforms and textures of one pass that every program of the pass
// reads, its precomputations' included: the scene, the clip plane, the
// transfer functions, the gradient volume and the renderer's parameters.
void RenderEngine::setPassUniforms(const ShaderProgram& prog, const Scene& scene, const Pass& pass,
                                   const PassInputs& inputs) {
    const Renderer& renderer = *pass.renderer;
    setSceneUniforms(prog, scene);
    prog.set("u_clip_point", pass.clipPoint);
    prog.set("u_clip_normal", pass.clipNormal);

    TransferFunctionSlot& slot = tf_[pass.slot];
    if (inputs.tf) {
        prog.set("u_tf_range", glm::vec2(float(slot.table.lo), float(slot.table.hi)));
        prog.set("u_tf_size", slot.table.size);
    }
    prog.set("u_tf", kTransferFunctionUnit);
    prog.set("u_gradient_volume", kGradientUnit);
    prog.set("u_bspline_coefficients", kBsplineUnit);

    const std::vector<Tf2dWidget>& widgets = inputs.widgets;
    prog.set("u_tf2d_count", int(widgets.size()));
    for (std::size_t i = 0; i < widgets.size(); ++i) {
        const Tf2dWidget& w = widgets[i];
        const std::string index = "[" + std::to_string(i) + "]";
        const bool box = w.kind == Tf2dWidget::Kind::Box;
        prog.set(("u_tf2d_kind" + index).c_str(), box ? 1 : 0);
        prog.set(("u_tf2d_shape" + index).c_str(),
                 box ? glm::vec4(w.valueRange.x, w.valueRange.y, w.gradientRange.x, w.gradientRange.y)
                     : glm::vec4(w.valueRange.x, w.radius, 0.0, 0.0));
        prog.set(("u_tf2d_color" + index).c_str(), glm::vec4(w.color, w.alpha));
    }
    renderer.setUniforms(prog, pass.values);
}

// The switches baked into a pass's program (see ShaderConstants): the
// interpolation, whether there is a transfer function, the pass's kind,
// every bool parameter, the number of 2D transfer-function widgets, and
// the label map's and second volume's own (scene_volumes.h).
ShaderConstants RenderEngine::switchesFor(const Scene& scene, const Pass& pass, const PassInputs& inputs,
                                          bool skipping, BrickCombine combine) const {
    const Renderer& renderer = *pass.renderer;
    ShaderConstants constants = {{"u_interpolation", int(scene.interpolation)},
                                 {"u_has_tf", inputs.tf ? 1 : 0},
                                 {"u_layer", pass.layer ? 1 : 0},
                                 {"u_clip_plane", pass.clip ? 1 : 0},
                                 {"u_clip_plane_count", int(std::min(scene.clipPlanes.size(), kMaxClipPlanes))},
                                 {"u_skipping", skipping ? 1 : 0},
                                 {"u_bricked", combine != BrickCombine::None ? 1 : 0},
                                 {"u_brick_combine", int(combine)},
                                 {"u_profile", profilePass_}};
    // Counting stays a uniform when asked (setCountingByUniform), except in
    // a bricked render, whose counting draws use programs of their own.
    if (!countingByUniform_ || combine != BrickCombine::None)
        constants["u_count_samples"] = countingSamples_ ? 1 : 0;
    for (const ParameterSpec& p : renderer.parameters())
        if (p.type == ParameterType::Bool) constants["u_" + p.name] = pass.values.at(p.name) != 0.0 ? 1 : 0;
    // The widget count makes a stage's loop over the widgets one with a
    // constant bound: it unrolls, and each widget's uniforms are read
    // directly instead of gathered per pixel (bonsai classified in 2D, 512x512 on
    // llvmpipe: 1.4-1.6 s to 0.8-0.9 s a frame, the same images). Adding or
    // removing a widget compiles again; moving one does not.
    if (renderer.needsTransferFunction2D()) constants["u_tf2d_count"] = int(inputs.widgets.size());
    sceneVolumes_->addConstants(scene, &constants);
    return constants;
}

// The transfer functions a pass reads: the pass's own, or a fallback over
// the scene's window (kept in `fallback`) for a renderer that needs one.
RenderEngine::PassInputs RenderEngine::passInputs(const Scene& scene, const Pass& pass,
                                                  std::optional<TransferFunction>& fallback) const {
    const Renderer& renderer = *pass.renderer;
    const glm::dvec2 window = scene.window.value_or(volume_->valueRange());
    PassInputs inputs;
    inputs.tf = pass.transferFunction;
    if (!inputs.tf && renderer.needsTransferFunction()) {
        fallback = defaultCompositingFunction(window);
        inputs.tf = &*fallback;
    }
    if (scene.transferFunction2D)
        inputs.widgets = scene.transferFunction2D->widgets();
    else if (renderer.needsTransferFunction2D())
        inputs.widgets = fallbackTransferFunction2D(window).widgets();
    return inputs;
}

// The transfer-function table, the gradients and the B-spline coefficients,
// uploaded when they changed and bound to their units.
void RenderEngine::bindTables(const Scene& scene, const Pass& pass, const PassInputs& inputs) {
    TransferFunctionSlot& slot = tf_[pass.slot];
    if (inputs.tf) uploadTransferFunction(slot, *inputs.tf);
    glActiveTexture(GL_TEXTURE0 + kTransferFunctionUnit);
    glBindTexture(GL_TEXTURE_2D, slot.texture);
    if (const auto estimator = pass.renderer->precomputedGradients(pass.values)) uploadGradients(*estimator);
    glActiveTexture(GL_TEXTURE0 + kGradientUnit);
    glBindTexture(GL_TEXTURE_3D, gradientTexture_);
    if (scene.interpolation == Interpolation::BSpline) uploadBsplineCoefficients();
    glActiveTexture(GL_TEXTURE0 + kBsplineUnit);
    glBindTexture(GL_TEXTURE_3D, bsplineTexture_);
}

// An object-order renderer: its geometry laid back to front over the
// background (or, for a cutting-plane layer, over nothing) in premultiplied
// alpha.
void RenderEngine::drawObjectOrder(const Scene& scene, const Pass& pass, const PassInputs& inputs,
                                   const ShaderProgram& prog, const ShaderConstants& constants) {
    const Camera cam = Camera::make(scene.camera, volume_->extent(), scene.width, scene.height);
    prog.set("u_clip_from_world", cam.clipFromWorld());
    const glm::vec4 under = pass.layer || reportingStubs_ ? glm::vec4(0.0f) : glm::vec4(scene.background, 1.0f);
    glClearColor(under.r, under.g, under.b, under.a);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    EngineDrawContext context(*this, scene, cam, prog, pass, inputs, constants);
    pass.renderer->draw(context, pass.values);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    // Drawn with its one program (not shear-warp's passes), whose opaque
    // stub pixels land as they are: they can say which stubs ran.
    if (programsNoted_ == 1 && !pass.layer) mainProgramStubs_ = prog.stubs();
}

// A ray caster's one full-screen triangle (only the tile's pixels when a
// tile is set: the others keep what they had).
void RenderEngine::drawFullScreen(const Pass& pass, const ShaderProgram& prog) {
    glDisable(GL_BLEND);
    glBindVertexArray(vao_);
    if (tile_ && !pass.layer) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(tile_->x, tile_->y, tile_->z, tile_->w);
        tiled_ = true;
    }
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_SCISSOR_TEST);
    if (!pass.layer) mainProgramStubs_ = prog.stubs();  // one pass: its pixels can say which stubs ran
}

namespace {

// The renderer's empty-space rule, with what the scene adds to it (nearest
// sampling's doubled gradient bounds, empty_space.h).
EmptySpaceRule skippingRule(const Scene& scene, const Renderer& renderer, const ParameterValues& values) {
    EmptySpaceRule rule = renderer.emptySpaceRule(values);
    if (scene.interpolation == Interpolation::Nearest) rule.gradientBoundScale = 2.0;
    return rule;
}

}  // namespace

void RenderEngine::draw(const Scene& scene, const Pass& pass) {
    const Renderer& renderer = *pass.renderer;
    std::optional<TransferFunction> fallback;
    const PassInputs inputs = passInputs(scene, pass, fallback);
    // A label map and a second volume (scene_volumes.h): loaded, checked and
    // uploaded before the program is chosen, so that a bad file fails first.
    // (The other side of a cutting plane may be drawn by a renderer that
    // ignores them.)
    if (pass.slot == 0) renderer.checkScene(scene, pass.values);
    checkHardwareFiltering(scene, *volume_);
    volumeTextures_->set(*volume_, volumeGeneration_, budgetFor(scene), maxTextureSize_);
    const BrickCombine combine = checkBricked(scene, pass);  // None: one texture
    sceneVolumes_->prepare(scene, *volume_, volumeGeneration_, inputs.tf);
    // The bricks know the first volume only: a fused second volume can show
    // anywhere. A cubic sample reads two voxels beyond its cell and may
    // overshoot the values it reads: the bricks' ranges do not bound it.
    const bool skipping =
        scene.skipEmptySpace && !renderer.objectOrder() && !scene.fusion && !isCubic(scene.interpolation);
    ShaderConstants constants = switchesFor(scene, pass, inputs, skipping, combine);
    const ShaderProgram& prog = program(renderer.vertexShader(), renderer.fragmentShader(), constants);
    lastRenderSources_.clear();
    lastRenderStubs_.clear();
    mainProgramStubs_.clear();
    programsNoted_ = 0;
    noteSources(prog);

    if (combine == BrickCombine::None) bindVolumeBrick(0, prog, scene);
    bindTables(scene, pass, inputs);

    // Precomputed textures first: they draw into framebuffers of their own
    // (never instrumented for the ray profile: the same textures, computed once).
    constants["u_skipping"] = 0;
    constants["u_profile"] = 0;
    const std::vector<Precomputation> precomputations = renderer.precomputations(scene, *volume_, pass.values);
    for (std::size_t i = 0; i < precomputations.size(); ++i)
        runPrecomputation(precomputations[i], int(i), scene, pass, inputs, constants);

    // With a label map a brick is empty only if no label's function shows it.
    const TransferFunctionTable* table =
        scene.labels ? &sceneVolumes_->labelUnionTable() : inputs.tf ? &tf_[pass.slot].table : nullptr;
    const auto prepare = [&](const ShaderProgram& p) {
        p.use();
        setPassUniforms(p, scene, pass, inputs);
        bindPrecomputations(p, precomputations, pass.slot);
        sceneVolumes_->bind(p, scene, *volume_);
        if (skipping) bindBricks(p, skippingRule(scene, renderer, pass.values), table, inputs.widgets);
        p.set("u_count_samples", countingSamples_ ? 1 : 0);  // ignored where switchesFor baked it
        p.set("u_report_stubs", reportingStubs_ ? 1 : 0);
    };
    prepare(prog);

    glDisable(GL_DEPTH_TEST);
    if (renderer.objectOrder()) {
        drawObjectOrder(scene, pass, inputs, prog, constants);
    } else if (combine != BrickCombine::None) {
        constants["u_skipping"] = skipping ? 1 : 0;
        drawBricked(scene, pass, inputs, prog, constants, combine, prepare);
    } else {
        drawFullScreen(pass, prog);
    }
    checkGlDraw(("drawing with renderer '" + renderer.id() + "'").c_str());
}

unsigned RenderEngine::sliceStack(int axis) {
    if (sliceStacks_[axis] && sliceStackGeneration_[axis] == volumeGeneration_) return sliceStacks_[axis];
    // Layer k of the stack for `axis` is the voxel layer at index k along it;
    // within a layer, the other two axes in cyclic order (axis+1, axis+2).
    const Volume& v = *volume_;
    v.requireInMemory("texture slicing's and shear-warp's slice stacks");
    const glm::ivec3 n = v.dims();
    const int a = axis, b = (axis + 1) % 3, c = (axis + 2) % 3;
    std::vector<float> texels(v.voxelCount());
    std::size_t out = 0;
    for (int k = 0; k < n[a]; ++k)
        for (int j = 0; j < n[c]; ++j)
            for (int i = 0; i < n[b]; ++i) {
                glm::ivec3 ijk;
                ijk[a] = k, ijk[b] = i, ijk[c] = j;
                texels[out++] = float(v.value(ijk.x, ijk.y, ijk.z));
            }
    // A new texture, filled before the old one goes (gl_object.h: softpipe
    // takes new storage where a deleted texture's was for that texture).
    GlTexture stack = GlTexture::make();
    glBindTexture(GL_TEXTURE_2D_ARRAY, stack);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32F, n[b], n[c], n[a], 0, GL_RED, GL_FLOAT, texels.data());
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    checkGlError("uploading a slice stack");
    sliceStacks_[axis] = std::move(stack);
    sliceStackGeneration_[axis] = volumeGeneration_;
    return sliceStacks_[axis];
}

RenderEngine::Pass RenderEngine::scenePass(const Scene& scene) const {
    Pass pass;
    pass.renderer = &renderers_.get(scene.renderer);
    pass.values = pass.renderer->resolveParameters(scene.parameters, volume_->valueRange());
    pass.transferFunction = scene.transferFunction ? &*scene.transferFunction : nullptr;
    if (scene.cuttingPlane) {
        const CuttingPlane& cut = *scene.cuttingPlane;
        pass.clip = true;
        pass.clipPoint = glm::vec3(cut.point.value_or(glm::dvec3(volume_->dims()) * 0.5) * volume_->spacing());
        pass.clipNormal = glm::vec3(glm::normalize(cut.normal));
    }
    return pass;
}

void RenderEngine::drawCut(const Scene& scene, unsigned framebuffer) {
    const CuttingPlane& cut = *scene.cuttingPlane;
    const glm::dvec2 range = volume_->valueRange();
    ensureLayers(scene.width, scene.height);
    glViewport(0, 0, scene.width, scene.height);

    Pass positive = scenePass(scene);
    positive.layer = true;
    const glm::vec3 point = positive.clipPoint, normal = positive.clipNormal;
    glBindFramebuffer(GL_FRAMEBUFFER, layers_[0].framebuffer);
    draw(scene, positive);

    glBindFramebuffer(GL_FRAMEBUFFER, layers_[1].framebuffer);
    if (cut.otherRenderer == "none") {
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    } else {
        Pass negative = positive;
        negative.renderer = &renderers_.get(cut.otherRenderer);
        negative.values = negative.renderer->resolveParameters(cut.otherParameters, range);
        negative.transferFunction = cut.otherTransferFunction ? &*cut.otherTransferFunction : nullptr;
        negative.slot = 1;
        negative.clipNormal = -normal;
        draw(scene, negative);
    }

    const ShaderProgram& compose = program("voxlab/fullscreen.vert", "voxlab/cut_compose.frag", {});
    compose.use();
    setSceneUniforms(compose, scene);
    compose.set("u_clip_point", point);
    compose.set("u_clip_normal", normal);
    for (int i = 0; i < 2; ++i) {
        glActiveTexture(GL_TEXTURE0 + kLayerUnit + i);
        glBindTexture(GL_TEXTURE_2D, layers_[i].color);
    }
    compose.set("u_layer_positive", kLayerUnit);
    compose.set("u_layer_negative", kLayerUnit + 1);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, scene.width, scene.height);
    glBindVertexArray(vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    checkGlDraw("composing the cutting plane's halves");
}

void RenderEngine::renderTo(const Scene& scene, unsigned framebuffer) {
    if (!volume_) throw Error("render: no volume has been set");
    tiled_ = false;
    if (scene.cuttingPlane) {
        drawCut(scene, framebuffer);
        return;
    }
    const Pass pass = scenePass(scene);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, scene.width, scene.height);
    draw(scene, pass);
}

void RenderEngine::renderOffscreen(const Scene& scene) {
    ensureTarget(scene.width, scene.height);
    renderTo(scene, target_.framebuffer);
}

Image RenderEngine::render(const Scene& scene) {
    renderOffscreen(scene);
    return readBack();
}

bool samplesCountable(const RendererRegistry& renderers, const Scene& scene) {
    const Renderer* renderer = renderers.find(scene.renderer);
    return renderer && !renderer->objectOrder() && !scene.cuttingPlane;
}

double RenderEngine::countSamples(const Scene& scene) {
    if (!samplesCountable(renderers_, scene))
        throw Error("counting samples: '" + scene.renderer +
                    "' scene: only ray-casting renderers without a cutting plane take samples that can be counted");
    countingSamples_ = true;
    try {
        renderOffscreen(scene);
    } catch (...) {
        countingSamples_ = false;
        throw;
    }
    countingSamples_ = false;
    const Image counts = readBack();
    double total = 0.0;
    for (std::size_t i = 0; i < counts.rgba.size(); i += 4) total += counts.rgba[i];
    return total;
}

std::vector<std::string> RenderEngine::stubsReached(const Scene& given, int maxSide) {
    if (lastRenderStubs_.empty()) return {};
    Scene scene = given;
    if (maxSide > 0 && std::max(scene.width, scene.height) > maxSide) {
        const double shrink = double(maxSide) / std::max(scene.width, scene.height);
        scene.width = std::max(1, int(scene.width * shrink)), scene.height = std::max(1, int(scene.height * shrink));
    }
    if (!stubTarget_.framebuffer || stubWidth_ != scene.width || stubHeight_ != scene.height) {
        stubTarget_.make(scene.width, scene.height);
        stubWidth_ = scene.width, stubHeight_ = scene.height;
    }
    const std::vector<std::string> compiled = lastRenderStubs_;
    reportingStubs_ = true;
    try {
        renderTo(scene, stubTarget_.framebuffer);
    } catch (...) {
        reportingStubs_ = false;
        throw;
    }
    reportingStubs_ = false;
    const std::vector<std::string> numbered = mainProgramStubs_;
    if (numbered.empty()) return compiled;  // several passes: their pixels do not say
    std::vector<float> pixels(std::size_t(scene.width) * scene.height * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, stubTarget_.framebuffer);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, scene.width, scene.height, GL_RGBA, GL_FLOAT, pixels.data());
    checkGlError("reading back the stubs reached");
    unsigned long bits = 0;
    for (std::size_t i = 0; i < pixels.size(); i += 4)
        if (pixels[i] >= 1.0f && pixels[i] < float(1 << kMaxNumberedStubs)) bits |= (unsigned long)(pixels[i]);
    std::vector<std::string> reached;
    for (std::size_t k = 0; k < numbered.size(); ++k)
        if (bits & (1ul << k)) reached.push_back(numbered[k]);
    return reached;
}

Image RenderEngine::readBack() const {
    const int width = fboWidth_, height = fboHeight_;
    Image image(width, height);
    std::vector<float> rows(image.rgba.size());
    glBindFramebuffer(GL_FRAMEBUFFER, target_.framebuffer);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rows.data());
    checkGlError("reading back the image");
    // GL's rows run bottom-up; images run top-down.
    const std::size_t rowFloats = std::size_t(width) * 4;
    for (int y = 0; y < height; ++y)
        std::copy_n(&rows[std::size_t(height - 1 - y) * rowFloats], rowFloats, &image.rgba[y * rowFloats]);
    return image;
}

}  // namespace voxlab
