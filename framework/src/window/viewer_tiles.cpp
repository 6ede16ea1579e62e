// voxlab viewer: a large image a band at a time.
//
// On a CPU rasteriser a 1080p frame of a ray caster takes seconds, and a
// frame of the UI waits for the render it contains: keys and the mouse went
// unanswered for as long. So an image expected to take longer than a
// frame's budget is rendered in bands of rows, top first, one band per
// frame (RenderEngine::setTile: the engine shades only the band's pixels),
// the band's height adapted so that each takes about kFrameBudgetMs. Until
// a band is done, the image shown before (the same scene at a reduced size,
// which the progressive refinement renders first) shows there. Anything
// that changes the scene cancels the bands and starts over.
#include "voxlab_gl.h"

#include <algorithm>
#include <cmath>

#include "viewer_state.h"

namespace voxlab::viewer {

namespace {

// Copies a side's image now on screen (w x h, in its engine's framebuffer)
// into its preview texture.
void copyPreview(Side& side, const RenderEngine& shown, int w, int h) {
    side.previewTexture.ensure();
    side.previewFbo.ensure();
    glBindTexture(GL_TEXTURE_2D, side.previewTexture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, side.previewFbo);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, side.previewTexture, 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, shown.offscreenFramebuffer());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void finishTiling(State& s) {
    Tiling& t = s.tiling;
    t.active = false;
    s.renderMs = t.ms;
    s.imageWidth = t.width, s.imageHeight = t.height;
    s.shownReduction = t.reduction;
    s.coarseShown = false;
    s.interactive = t.reduction > 1.0;  // more refinement steps to come
    if (!s.interactive) {
        s.refineStep = s.refineSteps = 0;
        updateStubNotice(s, t.mainScene);
    }
}

}  // namespace

bool tooSlowForOneFrame(const State& s, int w, int h) {
    return s.msPerPixel > 0.0 && s.msPerPixel * double(w) * double(h) > 2.0 * kFrameBudgetMs;
}

double reductionForBudget(const State& s) {
    const double pixels = double(s.fbWidth) * double(s.fbHeight);
    // Nothing measured yet (the first image): a quarter of the sides for a large window.
    if (s.msPerPixel <= 0.0) return pixels > 400000.0 ? 4.0 : 1.0;
    double r = 1.0;
    while (r < 16.0 && s.msPerPixel * pixels / (r * r) > kFrameBudgetMs) r *= 2.0;
    return r;
}

void startTiling(State& s, const Scene& mainScene, const Scene& otherScene, double reduction) {
    Tiling& t = s.tiling;
    t = Tiling();
    t.active = true;
    t.width = mainScene.width, t.height = mainScene.height;
    t.reduction = reduction;
    t.mainScene = mainScene, t.otherScene = otherScene;
    t.previewWidth = std::max(1, s.imageWidth), t.previewHeight = std::max(1, s.imageHeight);
    for (Side* side : {&s.main, &s.other})
        if (side->engine && (side == &s.main || s.split != SplitMode::Off))
            copyPreview(*side, shownEngine(s, *side), t.previewWidth, t.previewHeight);
    // The first band: what the last render's time per pixel lets a frame hold.
    t.rows = std::clamp(int(kFrameBudgetMs / std::max(s.msPerPixel * t.width, 1e-6)), 1, t.height);
    s.interactive = true;  // the image is not final: scripts wait, the idle loop does not sleep
    continueTiling(s);
}

void continueTiling(State& s) {
    Tiling& t = s.tiling;
    const int rows = std::min(t.rows, t.height - t.done);
    const glm::ivec4 band(0, t.height - t.done - rows, t.width, rows);  // GL's rows run bottom-up
    const auto t0 = Clock::now();
    bool tiled = true;
    for (Side* side : {&s.main, &s.other}) {
        if (!side->engine || (side == &s.other && s.split == SplitMode::Off)) continue;
        side->engine->setTile(band);
        renderSide(*side, side == &s.main ? t.mainScene : t.otherScene, false, false);
        side->engine->setTile(std::nullopt);
        tiled = tiled && side->engine->lastRenderTiled();
    }
    glFinish();
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    t.ms += ms;
    ++t.frames;
    const int rendered = tiled ? rows : t.height;  // a scene that cannot be tiled renders whole
    t.done = tiled ? t.done + rows : t.height;
    s.msPerPixel = ms / (double(rendered) * double(t.width));
    if (tiled && ms > 0.0) t.rows = std::clamp(int(double(rows) * kFrameBudgetMs / ms), 1, t.height);
    if (t.done >= t.height) finishTiling(s);
}

void cancelTiling(State& s) {
    s.tiling.active = false;
    s.interactive = false;
}

float tilingDoneFrom(const State& s) {
    if (!s.tiling.active || s.tiling.height <= 0) return 0.0f;
    return 1.0f - float(s.tiling.done) / float(s.tiling.height);
}

}  // namespace voxlab::viewer
