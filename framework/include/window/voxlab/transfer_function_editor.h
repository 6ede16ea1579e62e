// voxlab: transfer-function editors for the viewer, in the Dear ImGui style:
// free functions that take a pointer to the caller's data, draw themselves
// at the cursor through ImGui's draw lists, and return true on the frames
// where they changed it.
//
//  TransferFunctionEditor     the 1D function: control points over the
//                             volume's histogram;
//  TransferFunction2DEditor   the 2D function: Levoy triangles and boxes over
//                             the value x gradient-magnitude histogram;
//  TransferFunctionFiles,     a preset combo, a path, load and save;
//  TransferFunction2DFiles
//  EditHistory, ...UndoRedo   bounded undo/redo of either function.
//
// A typical panel:
//
//   static TransferFunctionHistory history;
//   static int selected = -1;
//   TransferFunctionEditorOptions o;
//   o.histogram = &hist, o.range = {volume.minValue(), volume.maxValue()};
//   bool changed = TransferFunctionFiles("files", &tf, volume.name(), &path, &message);
//   changed |= TransferFunctionEditor("##tf", &tf, o, &selected);
//   changed |= TransferFunctionUndoRedo(&history, &tf);
//
// Everything here is compiled only with the viewer (VOXLAB_HAVE_VIEWER;
// src/window/). The widgets need a current ImGui context; EditHistory,
// transferFunctionPresets, the load/save functions and histogram2DImage
// need none, and histogram2DTexture needs a current GL context.
//
// Dear ImGui here is Debian's 1.86: keys are read through io.KeyMap
// (GetKeyIndex(ImGuiKey_Delete) etc.), and ImGui floors mouse positions to
// whole pixels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/gradients.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"
#include "voxlab/volume.h"

namespace voxlab {

// ---------------------------------------------------------------------------
// 1D editor.
//
// Layout, from the cursor position c and the available width w:
//   graph frame  [c, c + (w, height + 2 pad)], pad = kTransferFunctionEditorPadding;
//   plot area    the frame inset by pad on every side (room for the handles at
//                the ends): x runs linearly over options.range, y over
//                opacity 0 (bottom) .. 1 (top);
//   below it     a strip of the colours, the range's two ends as labels (and
//                the visible part of `label`, the text before "##", between
//                them), then a row editing the selected point: colour (a
//                swatch that opens a picker), value, opacity, delete.
//
// Mouse: a left click on empty space adds a point there (its colour is the
// function's colour at that value) and keeps dragging it while the button is
// held; a left click on a handle selects it and drags it (value and
// opacity; grabbed where clicked, so it does not jump); a right click on a
// handle removes it. Delete or Backspace removes the selected point while
// the window has focus. A function keeps at least 2 points. Values stay in
// options.range, opacities in [0, 1], and the points stay sorted by value
// (a dragged point passing a neighbour changes places with it; *selected
// follows it). Points outside the plot are drawn on its edges and only move
// when dragged. The mouse wheel over the plot zooms the opacity axis (its
// top becomes 1/zoom, zoom 1 to 32, shown at the top left) for the small
// opacities of thick materials; the layout above is at zoom 1, the default.
constexpr float kTransferFunctionEditorPadding = 7.0f;

struct TransferFunctionEditorOptions {
    const Histogram* histogram = nullptr;  // drawn behind the curve when given
    bool logHistogram = true;              // log(1 + count); linear clips the tallest bin (see below)
    glm::dvec2 range{0.0, 1.0};            // the value axis, in the data's units (volume.valueRange())
    float height = 160.0f;                 // of the plot area, in pixels
    double valueSnap = 0.0;                // > 0: values are rounded to multiples of it (1 for integer data)
    bool showPointControls = true;         // the row editing the selected point
};

// `selected`: the selected point's index or -1; may be null (then the widget
// keeps its own). Returns true when *tf changed this frame.
bool TransferFunctionEditor(const char* label, TransferFunction* tf, const TransferFunctionEditorOptions& options,
                            int* selected);

// ---------------------------------------------------------------------------
// 2D editor.
//
// The plot shows value (x, the histogram's [valueLo, valueHi]) against
// gradient magnitude (y, 0 at the bottom up to gradientMax) with the 2D
// histogram behind it (log of the counts, as an image: a GL texture when the
// ImGui OpenGL3 backend and a GL context are there, otherwise a coarse grid
// of rectangles, so it also runs headless). Layout as in the 1D editor: the
// frame spans the available width and options.height + 2 pad pixels from the
// cursor; the plot is inset by kTransferFunctionEditorPadding. Below it:
// "+ triangle" and "+ box" buttons and a row for the selected widget.
//
// A triangle (Levoy) is drawn from its apex (value, 0) up to the top of the
// plot, its half-width radius * g at gradient magnitude g: drag the apex or
// the inside to move it along the value axis; drag the handle where either
// edge leaves the plot (its top corner, or the side it reaches first) to
// change the radius: the edge follows the mouse sideways. A box: drag the
// inside to move it, a corner to resize it. Double-click on empty space adds
// a triangle there; right-click on empty space offers a triangle or a box
// there; right-click on a widget (or Delete with the window focused) removes
// it. Widgets stay inside the histogram's domain; at most kMaxTf2dWidgets.
// The mouse wheel over the plot zooms the gradient axis (its top becomes
// gradientMax/zoom, zoom 1 to 64): most voxels have small gradients. The
// layout above is at zoom 1, the default.
struct TransferFunction2DEditorOptions {
    float height = 200.0f;     // of the plot area, in pixels
    bool logHistogram = true;  // log(1 + count), else linear
    bool showWidgetControls = true;
};

bool TransferFunction2DEditor(const char* label, TransferFunction2D* tf, const Histogram2D& histogram, int* selected,
                              const TransferFunction2DEditorOptions& options = {});

// The image behind the 2D editor, one byte per bin, row y = gradient bin y
// (row 0: gradient 0), x fastest: 255 * s(count) / s(maxCount) rounded, with
// s(c) = log(1 + c) (log) or c (linear); all zero when the histogram is.
std::vector<std::uint8_t> histogram2DImage(const Histogram2D& histogram, bool logScale = true);

// The same image as a GL texture (GL_R8, shown grey), kept in a small cache
// keyed by the histogram's address, size and contents, so a frame only
// uploads when the histogram changed. Needs a current GL context; returns 0
// when no GL functions are loaded. The texture belongs to the cache.
unsigned histogram2DTexture(const Histogram2D& histogram, bool logScale = true);

// Deletes the cached textures: call while the context is still current,
// before destroying it (ImGui_ImplOpenGL3_Shutdown time).
void releaseTransferFunctionEditorTextures();

// ---------------------------------------------------------------------------
// Undo/redo: a bounded list of states and a position in it.
//
// record(state) after an edit ends adds `state` when it differs from the
// current one (and drops whatever could have been redone); undo()/redo()
// step through the list and write the state into *state. undo() first
// records an edit that was not recorded yet, so nothing is lost. At most
// `depth` states are kept; the oldest go first.
inline bool sameEditState(const TransferFunction& a, const TransferFunction& b) { return a.points() == b.points(); }
inline bool sameEditState(const TransferFunction2D& a, const TransferFunction2D& b) {
    return a.widgets() == b.widgets();
}
template <typename State>
bool sameEditState(const State& a, const State& b) {
    return a == b;
}

template <typename State>
class EditHistory {
public:
    explicit EditHistory(std::size_t depth = 100) : depth_(depth < 2 ? 2 : depth) {}

    bool record(const State& state) {
        if (!states_.empty() && sameEditState(states_[current_], state)) return false;
        if (!states_.empty()) states_.erase(states_.begin() + std::ptrdiff_t(current_) + 1, states_.end());
        states_.push_back(state);
        if (states_.size() > depth_) states_.pop_front();
        current_ = states_.size() - 1;
        return true;
    }
    bool canUndo(const State& state) const {
        return !states_.empty() && (current_ > 0 || !sameEditState(states_[current_], state));
    }
    bool canRedo() const { return current_ + 1 < states_.size(); }
    bool undo(State* state) {
        record(*state);
        if (current_ == 0) return false;
        *state = states_[--current_];
        return true;
    }
    bool redo(State* state) {
        if (!canRedo()) return false;
        *state = states_[++current_];
        return true;
    }
    void clear() { states_.clear(), current_ = 0; }
    std::size_t size() const { return states_.size(); }

private:
    std::size_t depth_;
    std::deque<State> states_;
    std::size_t current_ = 0;
};

using TransferFunctionHistory = EditHistory<TransferFunction>;
using TransferFunction2DHistory = EditHistory<TransferFunction2D>;

// "undo" and "redo" buttons (and Ctrl+Z, Ctrl+Y or Ctrl+Shift+Z while the
// window has focus and no text is being typed). Call it once per frame after
// the editor: it also records *tf whenever no mouse button is held and no
// item is active, i.e. once an edit has ended. Returns true when *tf changed.
bool TransferFunctionUndoRedo(TransferFunctionHistory* history, TransferFunction* tf);
bool TransferFunctionUndoRedo(TransferFunction2DHistory* history, TransferFunction2D* tf);

// ---------------------------------------------------------------------------
// Presets and files.
//
// The JSON files in the `folder` (kTransferFunctionName or kTransferFunction2DName) of each dataset folder
// (those of $VOXLAB_DATA_PATH, then the project's datasets/): first those
// whose name starts with the dataset's stem ("bonsai" for "bonsai",
// "bonsai.nrrd", ".../bonsai.nrrd" or "phantom:bonsai:64"), then all others,
// each group sorted by name. Missing folders are skipped.
std::vector<std::string> transferFunctionPresets(const std::string& datasetName, const std::string& folder = kTransferFunctionName);

// What the buttons do, without a window: load (a relative path is found
// through the dataset search path) or save as JSON. On success *tf (or the
// file, atomically: see atomic_file.h) is replaced and *message says what
// was done; on failure *tf (or the file) is left as it was and *message
// reads "error: " and the reason. Never throws.
bool loadTransferFunctionFile(const std::string& path, TransferFunction* tf, std::string* message);
bool loadTransferFunctionFile(const std::string& path, TransferFunction2D* tf, std::string* message);
bool saveTransferFunctionFile(const std::string& path, const TransferFunction& tf, std::string* message);
bool saveTransferFunctionFile(const std::string& path, const TransferFunction2D& tf, std::string* message);

// A preset combo, a path field and load/save buttons. Choosing a preset loads
// it and sets *path; "load" (or Enter in the field) reads *path (found
// through the dataset search path when relative), "save" writes *tf there as
// JSON, after a confirmation when the file exists. The outcome is shown under
// the buttons and kept in *message; errors never reach the caller. Returns
// true when *tf changed.
bool TransferFunctionFiles(const char* label, TransferFunction* tf, const std::string& datasetName, std::string* path,
                           std::string* message);
bool TransferFunction2DFiles(const char* label, TransferFunction2D* tf, const std::string& datasetName,
                             std::string* path, std::string* message);

}  // namespace voxlab
