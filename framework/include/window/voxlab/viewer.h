// voxlab: the interactive viewer (GLFW + Dear ImGui).
#pragma once

#include <optional>
#include <string>

#include "voxlab/deck.h"
#include "voxlab/scene.h"

namespace voxlab {

struct ViewerOptions {
    std::string scenePath;           // the scene file `scene` was read from, as given ("" for none):
                                     // a student release finds a grading scene's expected image by it
    std::string implementationRoot;  // empty: reference/
    std::string studentRoot;         // the implementation switch's "student" side; empty: assignments/
    std::string script;              // a viewer script (viewer_script.h) to run instead of a person
    bool keepOpen = false;           // after the script, leave the window to a person
    std::optional<Deck> deck;        // a demo deck (deck.h): arrow keys step through its slides
    float uiScale = 1.0f;            // presentation mode: everything ImGui draws, times this
    // Scripted use (tests, README screenshots): render `frames` frames, save
    // a screenshot of the whole window to `screenshot`, and close.
    std::string screenshot;
    int frames = 0;
    int width = 1280;
    int height = 800;
};

// Opens the window on `scene` and runs until it is closed. Returns the exit code.
int runViewer(const Scene& scene, const ViewerOptions& options);

// The same viewer a frame at a time, for a loop that is not ours (the
// browser's: web/main_web.cpp). startViewer opens the window and loads the
// scene (throws voxlab::Error on failure); stepViewer draws one frame and
// returns false when the viewer is done; finishViewer releases everything and
// returns the exit code.
struct ViewerSession;
ViewerSession* startViewer(const Scene& scene, const ViewerOptions& options);
bool stepViewer(ViewerSession& session);
int finishViewer(ViewerSession* session);

// For a page that edits stage files itself (web/shell/workbench.js): show a
// scene file rendered by an implementation folder ("" is the reference, as
// in ViewerOptions; throws voxlab::Error, and the viewer is unchanged then);
// compile the stage files again now; and the main view's current error (a
// compiler message at file:line, or a render error), empty when its last
// render succeeded with freshly compiled shaders.
void viewerShowScene(ViewerSession& session, const std::string& scenePath, const std::string& implementationRoot);
void viewerReloadShaders(ViewerSession& session);
// The window's new size in pixels (the page's canvas was resized).
void viewerResize(ViewerSession& session, int width, int height);
// A dataset or scene file, as if dropped on the window (an error is shown there).
void viewerOpen(ViewerSession& session, const std::string& path);
std::string viewerError(const ViewerSession& session);
std::string viewerDataset(const ViewerSession& session);  // the path of the volume on screen
double viewerRenderMs(const ViewerSession& session);       // the last image's render time, as its status line says

}  // namespace voxlab
