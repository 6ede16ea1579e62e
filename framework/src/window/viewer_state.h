// voxlab viewer internals: what the window shows and how it got there.
// The viewer is split by concern: viewer.cpp (the frame loop and input),
// viewer_render.cpp (rendering both sides at interactive or full quality,
// the split view), viewer_panels.cpp (the ImGui panels), viewer_overlays.cpp
// (what is drawn over the image), viewer_script_runner.cpp (scripted steps),
// shader_watcher.cpp (live reload), viewer_style.cpp (the UI's size),
// viewer_deck.cpp (demo decks), viewer_stubs.cpp (the checkerboard's line).
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "voxlab/gl_object.h"
#include "voxlab/deck.h"
#include "voxlab/gradients.h"
#include "voxlab/ray_profile.h"
#include "voxlab/render_engine.h"
#include "voxlab/scene.h"
#include "voxlab/shader.h"
#include "voxlab/slice_viewer.h"
#include "voxlab/transfer_function_editor.h"
#include "voxlab/volume.h"

struct GLFWwindow;
struct ImFont;
struct ImDrawList;

namespace voxlab::viewer {

using Clock = std::chrono::steady_clock;

// Notices edits of shader files (by modification time, twice a second).
class ShaderWatcher {
public:
    // True when a file in `files` changed since the last call that saw it.
    bool changed(const std::vector<std::string>& files);

private:
    std::map<std::string, long long> stamps_;
    Clock::time_point lastCheck_{};
};

enum class SplitMode { Off, Split, Difference };

// One side of the view: an implementation and the engine that renders it.
struct Side {
    std::string implementation;  // a folder; empty: the reference
    std::string renderer;        // empty: the scene's
    std::unique_ptr<RenderEngine> engine;
    // The same implementation drawing the volume's coarse level while the
    // view moves (volume_pyramid.h); made on the first drag.
    std::unique_ptr<RenderEngine> coarse;
    std::string error;           // this side's last render error
    // While a large image is rendered a band at a time (viewer_tiles.cpp):
    // the image shown before it, under the bands not yet rendered.
    GlTexture previewTexture;
    GlFramebuffer previewFbo;
};

// A large image rendered a band of rows at a time, one band per frame, so
// that the UI keeps answering at the display's rate (viewer_tiles.cpp).
struct Tiling {
    bool active = false;
    int width = 0, height = 0;      // the image's size
    int done = 0;                   // rows finished, from the top
    int rows = 16;                  // rows the next band renders (adapts to the frame budget)
    int previewWidth = 0, previewHeight = 0;  // the size of the image shown under the rest
    double reduction = 1.0;         // the image's reduction (1: the window's size)
    double ms = 0.0;                // render time so far
    int frames = 0;                 // frames it has taken so far
    Scene mainScene, otherScene;
};

// A student release's split view compares with a shipped expected image
// (viewer_expected.cpp).
struct ExpectedImage {
    std::string key;         // the scene file and dataset it was found for
    std::string path;        // expected/<stage>/<scene>.png, or empty
    std::string why;         // why there is nothing to compare with
    bool available = false;
    Scene scene;             // the grading scene, at the image's size
    int width = 0, height = 0;
    GlTexture texture;
};

struct State {
    Scene scene;
    std::string scenePath;          // the scene last opened or saved
    std::string scenePathField;     // the panel's path field (save scene, open)
    std::unique_ptr<Volume> volume;
    Side main, other;               // `other` is the right side of a split view
    std::string studentRoot;        // the implementation switch's "student" folder
    SplitMode split = SplitMode::Off;
    float divider = 0.5f;           // fraction of the window's width
    ExpectedImage expected;         // a student release's right side
    bool hasReference = true;       // reference/ exists (not a student release); set at start

    // Rendering.
    bool dirty = true;              // the scene changed: render again
    bool interactive = false;       // the last images are reduced (mouse busy, or still refining)
    double reduction = 2.0;         // while busy: the image is the window's size divided by this
    double coarseReduction = 1.0;   // the same for the coarse level (below)
    // Progressive refinement: once the mouse rests, the reduced image is
    // rendered again at twice its resolution, frame by frame, up to the
    // window's; the UI answers between the steps.
    double shownReduction = 1.0;    // the last images' reduction (1: full quality)
    // Levels of detail: while the view moves, the volume's level
    // `coarseLevel` (each level halves every side; 0: the volume itself, too
    // small to need one) is drawn instead, at up to the window's size.
    int coarseLevel = 0;
    std::unique_ptr<Volume> coarseVolume;  // made on the first drag
    bool coarseShown = false;              // the last images are of the coarse level
    bool coarseWhileMoving = true;         // the panel's switch (script: lod on|off)
    int refineStep = 0, refineSteps = 0;  // the step the last images were (0 while dragging)
    Clock::time_point lastInput{};
    Clock::time_point lastRetry{};  // a side whose shader never compiled is retried every second
    double renderMs = 0.0, frameMs = 0.0;
    int fbWidth = 0, fbHeight = 0;  // framebuffer pixels
    float contentScale = 1.0f;      // the UI's scale: the window's high-DPI scale times uiScale
    float windowScale = 1.0f;       // the window's high-DPI scale
    float uiScale = 1.0f;           // presentation mode: --ui-scale and the + and - keys
    bool relayout = true;           // place the panels for the current scale (the next frame)
    float requestedUiScale = 0.0f;  // a key asked for this scale (0: none), applied between frames
    int imageWidth = 0, imageHeight = 0;  // size of the images last rendered
    Tiling tiling;                  // a large image in progress, a band per frame
    double msPerPixel = 0.0;        // the last render's time per pixel (both sides), to plan the next
    // Key presses since the last frame (key, modifiers), through GLFW's key
    // callback: a key pressed and released while a frame took long is
    // still seen (ImGui 1.86 keeps only the keys down at the frame's start).
    std::vector<std::pair<int, int>> keyPresses;
    std::string lastScreenshot;     // the status line names where P saved it (absolute) ...
    Clock::time_point lastScreenshotUntil{};  // ... until then
    // The samples view: each pixel coloured by the samples its ray took
    // (RenderEngine::countSamples), on a scale where yellow is the most a
    // ray through the box's diagonal can take; the left (or only) side's
    // total and the README's count for the same frame.
    bool showSamples = false;
    bool samplesShown = false;  // the last images are counts (a ray caster without a cutting plane)
    float countScale = 1.0f;
    double samplesTaken = 0.0, samplesFull = 0.0;

    // Mouse.
    bool dragging = false, panning = false, draggingDivider = false;
    double pressX = 0, pressY = 0, lastX = 0, lastY = 0;
    bool moved = false;

    // Panels.
    float panelRight = 0.0f;        // the control panel's right edge (the transfer function goes beside it)
    bool tfPanelCompact = false;    // the transfer-function panel shows no editor (none in use)
    bool showPanel = true, showTransferFunction = true, showSlices = false, showProfile = false, showHelp = false;
    int selectedPoint = -1, selectedWidget = -1;
    TransferFunctionHistory history;
    std::optional<Histogram> histogram;
    std::optional<Histogram2D> histogram2D;
    std::string tfPath, tfMessage;
    SliceCursor slices;
    std::unique_ptr<SliceViewer> sliceViewer;
    std::optional<RayProfile> profile;
    glm::ivec2 profilePixel{0};     // framebuffer pixel the profile was taken at
    CameraSpec profileCamera;       // ... with this camera (the marker shows while it is the same)
    ShaderWatcher watcher;
    std::unique_ptr<ShaderProgram> presenter;  // shaders/viewer/split_view.frag
    GlVertexArray presenterVao;

    // The scene's other volumes and clip planes (viewer_scene_volumes.cpp).
    int editedLabel = -1;            // the label class whose function the editor edits; -1: the scene's
    std::string labelPathField, fusionPathField;
    std::vector<std::uint64_t> labelCounts;  // voxels per label of the label map ...
    std::string labelCountsPath;             // ... read from this file
    int draggingPlane = -1;          // the clip plane whose handle the mouse drags

    // A demo deck (voxlab/deck.h): the slide shown, stepped by arrow keys.
    std::optional<Deck> deck;
    int slide = 0;

    // The current side's functions that still hold the starter code's stub
    // (the checkerboard), as one line; empty when none.
    std::string stubNotice;

    // Messages: a load error or "saved screenshot" for a few seconds.
    std::string toast;
    Clock::time_point toastUntil{};
    std::vector<std::string> dropped;  // files dropped on the window, loaded next frame
    std::string screenshotRequest;     // a path: save the window after this frame
    bool screenshotByKey = false;      // ... asked for by P (or the panel's button): say where it went

    void say(const std::string& message, double seconds = 4.0) {
        toast = message;
        toastUntil = Clock::now() + std::chrono::milliseconds(int(seconds * 1000));
    }
};

// viewer_render.cpp
void loadDataset(State& s, const std::string& pathOrScene);  // throws voxlab::Error; the state is unchanged then
void setScene(State& s, const Scene& scene, const std::string& scenePath);  // the same for a parsed scene
// The transfer-function preset (datasets/tf/) equal to the scene's, or "".
std::string presetOf(const Scene& scene, const Volume& volume);
void setImplementation(Side& side, const std::string& root, const Volume& volume);
// Renders one side (its engine, or the coarse one), or counts its samples;
// returns the samples counted (0 when rendering). A failure is the side's error.
double renderSide(Side& side, const Scene& scene, bool countSamples, bool coarse);
// After s.volume changed: its coarse level is chosen (and made on the
// next drag).
void resetCoarseLevel(State& s);
// Compiles both sides' shaders again (the R key, the panel's button).
void reloadShaders(State& s);
// The engine whose image the side shows now (the coarse one while moving).
const RenderEngine& shownEngine(const State& s, const Side& side);
// What the coarse level shows while moving, after "level N": ", GPU filtering"
// when it reads between voxels with the GPU's filtering instead of the scene's
// interpolation (see sideScene), else "".
std::string coarseFiltering(const Scene& scene);
void renderFrame(State& s);          // renders what is dirty, at the right quality
void presentFrame(State& s);         // draws the images into the window
void saveWindowScreenshot(int width, int height, const std::string& path);
void pickRayProfile(State& s, glm::ivec2 pixel);  // framebuffer pixel; opens the ray-profile panel
std::string timestampedScreenshotName();

// viewer_tiles.cpp: a large image a band at a time.
constexpr double kFrameBudgetMs = 25.0;  // rendering's share of a frame while the UI must answer
// Whether the image of `w` x `h` pixels is expected to take longer than a
// frame's budget (from the last render's time per pixel).
bool tooSlowForOneFrame(const State& s, int w, int h);
// The reduction (1, 2, 4, 8 or 16) whose image is expected to fit a frame's budget.
double reductionForBudget(const State& s);
// Starts rendering the sides' scenes (at w x h) in bands; the image shown
// now stays under the bands not yet rendered.
void startTiling(State& s, const Scene& mainScene, const Scene& otherScene, double reduction);
void continueTiling(State& s);  // renders the next band; finishes the image after the last
void cancelTiling(State& s);    // the scene changed: the next render starts over
// For the presenter: the row (from the bottom, in the image's rows) from
// which the image is new; 0 when it is all new.
float tilingDoneFrom(const State& s);
// Records a key press for handleKeys and passes the event on to ImGui (the
// GLFW key callback; a script's `key` and `press` steps come this way too).
void keyEvent(GLFWwindow* window, int key, int scancode, int action, int mods);

// viewer_expected.cpp
bool comparesWithExpected(const State& s);  // split view without a reference
void updateExpected(State& s);            // finds and loads the current scene's expected image


// viewer_stubs.cpp
// After a full-quality image of `scene`: the line naming the stubs it reached.
void updateStubNotice(State& s, const Scene& scene);

// viewer_panels.cpp, viewer_overlays.cpp
void drawPanels(State& s);
void drawOverlays(State& s);
std::string parameterLabel(const std::string& name);  // "early_termination" -> "early termination"

// viewer_scene_volumes.cpp: the labels, fusion and clip-plane sections of
// the control panel (true when the scene changed), and the clip planes'
// widgets over the image (display coordinates).
bool sceneVolumeSections(State& s);
struct ClipPlaneHandle {
    bool visible = false;
    glm::vec2 centre{0.0f}, tip{0.0f};  // the handle and its arrow along the normal
    double arrowLength = 0.0;           // world units the arrow stands for
    std::vector<glm::vec2> outline;     // the plane's polygon on the box
};
std::vector<ClipPlaneHandle> clipPlaneHandles(const State& s);
void drawClipPlanes(const State& s, ImDrawList* fg);
int clipPlaneAt(const State& s, double x, double y);  // the plane whose handle is there, or -1
void dragClipPlane(State& s, int index, double dx, double dy);

// viewer_style.cpp
float clampUiScale(float scale);  // to quarter steps in [0.75, 4]
// Rebuilds the font at the new size and scales the style; sets uiScale,
// contentScale and relayout. Between frames only (not inside NewFrame..Render).
void applyUiScale(State& s, float userScale, float windowScale);
ImFont* captionFont();  // the large font of a deck's captions (the regular one without a TTF)

// viewer_deck.cpp
void showSlide(State& s, int index);  // clamps; loads the slide's dataset when it differs

}  // namespace voxlab::viewer
