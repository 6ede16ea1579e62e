// voxlab viewer: rendering both sides of the view at the right quality, and
// putting the images on the screen.
//
// While the mouse drags (and for a moment after the wheel turns) the
// renderers draw a coarser level of the volume (volume_pyramid.h: each
// level halves every side, a mean of 2x2x2 voxels) at up to the window's
// resolution, or, for a volume too small to need one or a scene whose parts
// are tied to the full grid (a region of interest, a cutting plane, a label
// map), the volume itself at a fraction of the resolution and twice the
// step: either keeps the frame rate up on a software rasteriser. Once input stops,
// the image is refined progressively: each frame renders twice the last
// resolution at the full step, until the window's resolution arrives. A
// projector never shows the blurred image for long, and the UI still answers
// between the steps (a new drag starts over at once).
#include "voxlab_gl.h"

#include <cmath>
#include <ctime>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "viewer_state.h"
#include "voxlab/error.h"
#include "voxlab/ray_profile.h"
#include "voxlab/shader.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume_pyramid.h"

namespace voxlab::viewer {

namespace {

constexpr auto kSettle = std::chrono::milliseconds(250);  // idle time before full quality
constexpr double kInteractiveMs = 80.0;  // what a render aims at while the mouse is busy (10 frames/s with the rest)
// The coarse level's size: at most about this many voxels (bonsai's 256^3
// moves at 128^3, a 1024^3 volume at 128^3).
constexpr double kCoarseVoxels = double(1 << 22);

bool isSceneFile(const std::string& path) {
    return path.size() > 5 && path.substr(path.size() - 5) == ".json";
}

// Whether the coarse level reads between voxels with the GPU's filtering
// instead of the scene's interpolation: all but nearest-neighbour.
bool coarseFiltersOnGpu(const Scene& scene) { return scene.interpolation != Interpolation::Nearest; }

// The scene one side renders: the shared scene with that side's renderer.
// `doubleStep`: twice the step (while moving). `coarse`: drawn from the
// coarse level, which reads between voxels with the GPU's filtering: a
// preview while moving (the status line says so), at about half the time
// per sample of the sampling stage's eight reads.
Scene sideScene(const State& s, const Side& side, int width, int height, bool doubleStep, bool coarse) {
    Scene scene = s.scene;
    if (!side.renderer.empty() && side.renderer != scene.renderer) {
        scene.renderer = side.renderer;
        scene.parameters.clear();
    }
    scene.width = width;
    scene.height = height;
    if (doubleStep) scene.step = std::min(kMaxStep, scene.step * 2.0);
    if (coarse && coarseFiltersOnGpu(scene)) scene.interpolation = Interpolation::Hardware;
    return scene;
}

// Whether the scene can be drawn from the coarse level: its parts given in
// the full grid's voxels (a region of interest, a cutting plane's point, a
// label map, a second volume's resampling) would not line up.
bool coarseDrawable(const State& s) {
    return s.coarseWhileMoving && s.coarseLevel > 0 && !s.scene.roi && !s.scene.cuttingPlane && !s.scene.labels && !s.scene.fusion;
}

// The coarse level and each side's engine for it, made on first use.
void prepareCoarse(State& s) {
    if (!s.coarseVolume) {
        Volume level = halveVolume(*s.volume);
        for (int l = 1; l < s.coarseLevel; ++l) level = halveVolume(level);
        s.coarseVolume = std::make_unique<Volume>(std::move(level));
    }
    for (Side* side : {&s.main, &s.other})
        if (side->engine && !side->coarse) {
            side->coarse = std::make_unique<RenderEngine>(side->engine->renderers(), side->engine->implementationRoot());
            side->coarse->setVolume(*s.coarseVolume);
        }
}

}  // namespace

// Renders one side, or counts its samples in the samples view. Returns
// the samples counted (0 when rendering normally).
double renderSide(Side& side, const Scene& scene, bool countSamples, bool coarse) {
    RenderEngine& engine = coarse ? *side.coarse : *side.engine;
    try {
        double taken = 0.0;
        if (countSamples) taken = engine.countSamples(scene);
        else engine.renderOffscreen(scene);
        side.error.clear();
        return taken;
    } catch (const Error& e) {
        side.error = e.what();  // the last good image stays
    }
    return 0.0;
}

void setImplementation(Side& side, const std::string& root, const Volume& volume) {
    auto engine = std::make_unique<RenderEngine>(rendererRegistry(), root);  // throws for a folder that does not exist
    engine->setVolume(volume);
    side.engine = std::move(engine);
    side.coarse.reset();  // made again, with this implementation, on the next drag
    side.implementation = root;
    side.error.clear();
}

void resetCoarseLevel(State& s) {
    s.coarseLevel = coarseLevelFor(s.volume->dims(), kCoarseVoxels);
    s.coarseVolume.reset();
    s.main.coarse.reset(), s.other.coarse.reset();
    s.coarseShown = false;
}

void reloadShaders(State& s) {
    for (Side* side : {&s.main, &s.other}) {
        if (side->engine) side->engine->reloadShaders();
        if (side->coarse) side->coarse->reloadShaders();
    }
    s.dirty = true;
}

std::string coarseFiltering(const Scene& scene) {
    return coarseFiltersOnGpu(scene) ? ", GPU filtering" : "";
}

const RenderEngine& shownEngine(const State& s, const Side& side) {
    return s.coarseShown && side.coarse ? *side.coarse : *side.engine;
}

void loadDataset(State& s, const std::string& path) {
    if (isSceneFile(path)) return setScene(s, Scene::load(path), path);
    Scene scene = s.scene;
    scene.dataset = resolveDataPath(path);
    scene.window.reset();  // the old dataset's window and colours mean nothing here
    scene.transferFunction.reset();
    scene.transferFunction2D.reset();
    scene.roi.reset();
    scene.cuttingPlane.reset();
    scene.labels.reset();  // on another grid
    scene.fusion.reset();
    scene.clipPlanes.clear();
    setScene(s, scene, s.scenePath);
}

void setScene(State& s, const Scene& scene, const std::string& scenePath) {
    if (scene.dataset != s.scene.dataset || !s.volume) {  // a deck's slides often share one volume
        auto volume = std::make_unique<Volume>(loadVolume(scene.dataset));
        s.main.engine->setVolume(*volume);
        if (s.other.engine) s.other.engine->setVolume(*volume);
        s.volume = std::move(volume);
        resetCoarseLevel(s);
        s.histogram.reset();
        s.histogram2D.reset();
        s.slices = initialSliceCursor(*s.volume);
        if (s.sliceViewer) s.sliceViewer->invalidate();
    }
    s.scene = scene;
    s.scenePath = scenePath;
    s.tfPath = presetOf(scene, *s.volume);  // the panel shows a preset's name
    s.tfMessage.clear();
    s.profile.reset();
    s.history = TransferFunctionHistory();
    s.editedLabel = -1;
    s.labelCountsPath.clear();  // counted again against this scene's volume
    s.dirty = true;
}

std::string presetOf(const Scene& scene, const Volume& volume) {
    if (!scene.transferFunction) return "";
    const nlohmann::json mine = scene.transferFunction->toJson();
    for (const std::string& preset : transferFunctionPresets(volume.name())) {
        try {
            if (TransferFunction::load(preset).toJson() == mine) return preset;
        } catch (const Error&) {  // a broken preset is the editor's to report
        }
    }
    return "";
}

// Hold about 10 frames/s while the mouse is busy: scale the moving image's
// sides by the square root of render time over the aim (the time goes with
// the pixels), growing at most 25 % a frame, and leave it alone within 10 %
// of the aim, where frame times jitter (the full level: from half to an
// eighth of the window's size on each side; the coarse level: from the whole
// window down to an eighth). An earlier rule grew the image only below half
// the budget, and left it wherever it landed between half and all of it:
// bonsai, composited, moved at 60 ms a frame and a smaller image than it could.
static void adaptReduction(State& s, bool coarse) {
    double& r = coarse ? s.coarseReduction : s.reduction;
    const double largest = coarse ? 1.0 : 2.0;
    const double ratio = s.renderMs / kInteractiveMs;
    if (ratio > 1.1) r = std::min(8.0, r * std::sqrt(ratio));
    else if (ratio < 0.9) r = std::max(largest, r / std::min(1.25, std::sqrt(1.0 / std::max(ratio, 1e-3))));
}

namespace {

// A student release: the grading scene as graded, against its expected image.
void renderExpectedSide(State& s) {
    updateExpected(s);
    const auto t0 = Clock::now();
    s.samplesShown = false;
    if (s.expected.available) renderSide(s.main, s.expected.scene, false, false);
    if (s.expected.available) updateStubNotice(s, s.expected.scene);
    glFinish();
    s.renderMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    s.imageWidth = s.expected.width, s.imageHeight = s.expected.height;
    s.interactive = false;
    s.dirty = false;
}

// Both sides at once (or their sample counts), and what the next frame
// needs to know of it.
void renderWhole(State& s, const Scene& mainScene, const Scene& otherScene, bool coarse, bool dragging) {
    const Volume& shown = coarse ? *s.coarseVolume : *s.volume;
    const auto t0 = Clock::now();
    s.samplesShown =
        s.showSamples && samplesCountable(rendererRegistry(), mainScene) && (s.split == SplitMode::Off || samplesCountable(rendererRegistry(), otherScene));
    s.samplesTaken = renderSide(s.main, mainScene, s.samplesShown, coarse);
    if (s.split != SplitMode::Off) renderSide(s.other, otherScene, s.samplesShown, coarse);
    glFinish();
    s.renderMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (!coarse && !s.samplesShown) s.msPerPixel = s.renderMs / (double(mainScene.width) * mainScene.height);
    if (s.samplesShown) {
        // The scale: the samples along the box's diagonal at this frame's step.
        const double most = glm::length(shown.extent()) / (mainScene.step * shown.minSpacing());
        s.countScale = float(1.0 / std::max(most, 1.0));
        s.samplesFull = samplesByRule(shown, mainScene);
    }
    s.imageWidth = mainScene.width, s.imageHeight = mainScene.height;
    if (dragging) adaptReduction(s, coarse);
    s.coarseShown = coarse;
}

}  // namespace

void renderFrame(State& s) {
    // A side whose program has never compiled has no files to watch yet:
    // try it again every second, so that saving the fix shows the image.
    if (Clock::now() - s.lastRetry > std::chrono::seconds(1)) {
        s.lastRetry = Clock::now();
        for (const Side* side : {&s.main, &s.other})
            if (side->engine && !side->error.empty()) reloadShaders(s);
    }
    // Live reload: a saved shader file recompiles at once.
    if (s.main.engine && s.watcher.changed(s.main.engine->shaderSources())) reloadShaders(s);
    for (Side* side : {&s.main, &s.other})  // wireframes as wide as the UI's scale makes its lines
        for (RenderEngine* engine : {side->engine.get(), side->coarse.get()})
            if (engine) engine->setLineWidth(s.contentScale);
    const bool busy = s.dragging || s.panning || Clock::now() - s.lastInput < kSettle;
    // A large image in progress: its next band, unless the scene changed.
    if (s.tiling.active && !s.dirty) return continueTiling(s);
    if (s.tiling.active) cancelTiling(s);
    // Nothing new to show: unless the last images are reduced and the
    // mouse has settled, keep them.
    if (!s.dirty && !(s.interactive && !busy)) return;
    if (s.fbWidth <= 0 || s.fbHeight <= 0) return;
    if (comparesWithExpected(s)) return renderExpectedSide(s);
    // While the mouse is busy: the coarse level (or the reduced size and
    // twice the step). Once it rests: the full level at twice the last
    // resolution each frame, full step, up to full size. A change made
    // without the mouse (a key, a slide) starts at the size that fits a frame.
    const bool dragging = busy && s.dirty;
    const bool coarse = dragging && coarseDrawable(s);
    const bool refining = !s.dirty && s.interactive;
    double reduction = 1.0;
    if (dragging) {
        reduction = coarse ? s.coarseReduction : s.reduction;
        s.refineSteps = std::max(int(std::ceil(std::log2(reduction) - 1e-9)), coarse ? 1 : 0);
        s.refineStep = 0;
    } else if (refining) {
        reduction = std::max(1.0, s.shownReduction * 0.5);
        s.refineStep = std::min(s.refineStep + 1, s.refineSteps);
    } else if (!s.showSamples) {
        reduction = reductionForBudget(s);
        s.refineSteps = int(std::ceil(std::log2(reduction) - 1e-9));
        s.refineStep = 0;
    }
    const bool reduced = reduction > 1.0;
    const int w = reduced ? std::max(1, int(s.fbWidth / reduction)) : s.fbWidth;
    const int h = reduced ? std::max(1, int(s.fbHeight / reduction)) : s.fbHeight;
    if (s.split != SplitMode::Off && !s.other.engine) setImplementation(s.other, "", *s.volume);
    if (coarse) prepareCoarse(s);
    const Scene mainScene = sideScene(s, s.main, w, h, dragging, coarse);
    Scene otherScene;
    if (s.split != SplitMode::Off) otherScene = sideScene(s, s.other, w, h, dragging, coarse);
    s.dirty = false;
    // A refinement step too large for one frame: a band of rows per frame.
    if (refining && !s.showSamples && tooSlowForOneFrame(s, w, h))
        return startTiling(s, mainScene, otherScene, reduction);
    renderWhole(s, mainScene, otherScene, coarse, dragging);
    s.interactive = reduced || coarse;
    s.shownReduction = reduction;
    if (!s.interactive) s.refineStep = s.refineSteps = 0;
    if (!s.interactive) updateStubNotice(s, mainScene);
}

void presentFrame(State& s) {
    if (!s.presenter) {
        const ShaderLibrary library({projectRoot() + "/shaders"});
        s.presenter = std::make_unique<ShaderProgram>(library, "voxlab/fullscreen.vert", "viewer/split_view.frag");
        s.presenterVao = GlVertexArray::make();
    }
    const ShaderProgram* program = s.presenter.get();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, s.fbWidth, s.fbHeight);
    glDisable(GL_BLEND);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (!s.main.engine || !shownEngine(s, s.main).offscreenTexture()) return;
    const bool expected = comparesWithExpected(s);
    if (expected && !s.expected.available) return;  // the overlay says why
    const bool split =
        expected || (s.split != SplitMode::Off && s.other.engine && shownEngine(s, s.other).offscreenTexture());
    const unsigned mainTexture = shownEngine(s, s.main).offscreenTexture();
    const unsigned textures[2] = {mainTexture, expected ? s.expected.texture
                                               : split  ? shownEngine(s, s.other).offscreenTexture()
                                                        : mainTexture};
    for (int i = 0; i < 2; ++i) {
        glActiveTexture(GL_TEXTURE0 + i);
        glBindTexture(GL_TEXTURE_2D, textures[i]);
        // Reduced images are filtered up to the window.
        const GLint filter = s.interactive && !expected && !s.tiling.active ? GL_LINEAR : GL_NEAREST;
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    }
    // Under the bands of a large image not yet rendered: the images shown before.
    const unsigned previews[2] = {s.tiling.active ? s.main.previewTexture : textures[0],
                                  s.tiling.active && split && s.other.previewTexture ? s.other.previewTexture
                                                                                     : textures[1]};
    for (int i = 0; i < 2; ++i) {
        glActiveTexture(GL_TEXTURE2 + i);
        glBindTexture(GL_TEXTURE_2D, previews[i]);
    }
    program->use();
    program->set("u_left", 0);
    program->set("u_right", 1);
    program->set("u_left_preview", 2);
    program->set("u_right_preview", 3);
    program->set("u_new_from", expected ? 0.0f : tilingDoneFrom(s));
    program->set("u_viewport_size", glm::vec2(s.fbWidth, s.fbHeight));
    program->set("u_divider", s.divider * float(s.fbWidth));
    program->set("u_mode", !split ? 0 : s.split == SplitMode::Split ? 1 : 2);
    program->set("u_count_scale", s.samplesShown ? s.countScale : 0.0f);
    // An expected image keeps its shape: both sides letterboxed, pixels sharp.
    program->set("u_image_aspect", expected ? float(s.expected.width) / float(s.expected.height) : 0.0f);
    glBindVertexArray(s.presenterVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glActiveTexture(GL_TEXTURE0);
}

void pickRayProfile(State& s, glm::ivec2 pixel) {
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= s.fbWidth || pixel.y >= s.fbHeight) return;
    Scene scene = s.scene;
    scene.width = s.fbWidth, scene.height = s.fbHeight;
    const bool right = s.split == SplitMode::Split && pixel.x >= s.divider * s.fbWidth;
    if (right && !s.other.renderer.empty()) scene.renderer = s.other.renderer, scene.parameters.clear();
    // The side's own engine: its implementation's stages are the ones the
    // profile shows (the student's on the left, the other side's on the right).
    RenderEngine& engine = right && s.other.engine ? *s.other.engine : *s.main.engine;
    try {
        s.profile = engine.profileRay(scene, pixel.x, pixel.y);
    } catch (const Error& e) {  // a shader that does not compile, say: the image keeps its last good one
        s.say(std::string("ray profile: ") + e.what(), 6.0);
        return;
    }
    s.profilePixel = pixel;
    s.profileCamera = s.scene.camera;
    s.showProfile = true;
}

void saveWindowScreenshot(int width, int height, const std::string& path) {
    Image img(width, height);
    std::vector<unsigned char> rows(std::size_t(width) * height * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const unsigned char* p = &rows[(std::size_t(height - 1 - y) * width + x) * 4];
            img.set(x, y, glm::vec4(p[0], p[1], p[2], 255) / 255.0f);
        }
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    std::error_code ec;  // a voxlab::Error on failure, not a filesystem_error the viewer would not catch
    if (!parent.empty() && !std::filesystem::create_directories(parent, ec) && ec)
        throw Error(path + ": cannot create the folder " + parent.string() + ": " + ec.message());
    savePng(img, path);
}

std::string timestampedScreenshotName() {
    const std::time_t now = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "voxlab_%Y%m%d_%H%M%S.png", std::localtime(&now));
    return buf;
}

}  // namespace voxlab::viewer
