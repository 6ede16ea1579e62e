// voxlab: viewer scripts, the steps that `voxlab view --script FILE` plays
// to drive the viewer without a person (CI, README screenshots).
//
// One step per line: a command and its arguments, separated by blanks.
// `#` outside double quotes starts a comment; blank lines are skipped; an
// argument with blanks or `#` goes in double quotes ("my data/a b.nrrd").
//
//   load PATH                      a dataset or a scene .json (resolveDataPath)
//   scene PATH                     a scene .json
//   renderer NAME
//   param NAME VALUE               a renderer parameter: a number, true or false
//   step X                         sampling step (voxels), > 0
//   interpolation nearest|trilinear|hardware|bspline|catmull-rom
//   tf PATH|none                   a transfer-function file, or none
//   TF2D PATH|none                 a 2D transfer-function file, or none (TF2D: the 2D
//                                  transfer function's name, kTransferFunction2DName)
//   camera SETTING VALUE...        settings: azimuth A, elevation E, distance D,
//                                  fov F, zoom Z, pan X Y, view +x|-x|+y|-y|+z|-z,
//                                  projection perspective|orthographic
//   rotate AZIMUTH ELEVATION       orbit by degrees
//   drag DX DY FRAMES              orbit with the mouse for FRAMES frames, (DX, DY) pixels each,
//                                  as a person would (reduced quality), then let it settle;
//                                  prints the median render time while dragging and the
//                                  full-quality render time after
//   window LO HI                   grey window in data units, HI > LO
//   skipping on|off                empty-space skipping (the scene's sampling.skip_empty_space)
//   samples on|off                 the samples view: pixels coloured by the samples their rays take
//   lod on|off                     while the view moves, draw the coarse level (volume_pyramid.h)
//   split on|off|difference        student | reference side by side, or the heat map
//   divider X                      the split's divider at X (0..1) of the window's width
//   right RENDERER|same            the right side's technique (default: the same as the left)
//   implementation DIR|reference|student   what the left side (or the only view) runs
//   panel slices|tf|TF2D|profile|help|controls on|off   (viewerPanels(), below)
//   enlarge axial|coronal|sagittal|off   the slices panel with one view enlarged (off: all three)
//   click X Y                      a left click at window pixel (X, Y)
//   drag-plane N DX DY             press on clip plane N's handle (1-based; it must be
//                                  there to grab) and move the mouse by (DX, DY) window pixels
//   key left|right|up|down|pageup|pagedown|home|end|plus|minus|p
//                                  press and release a key, as a person would (a deck's
//                                  arrows, the UI scale's + and -, P's screenshot)
//   press KEY...                   press and release each key at once, in the same frame,
//                                  without waiting for the image to be finished (a person
//                                  typing while a large frame renders); prints what was
//                                  rendering when the keys came
//   rendering                      wait, without waiting for the image to be finished, until
//                                  the viewer renders a large image a band of rows per frame
//                                  and has more than two bands to go
//   ui-scale X                     the UI's scale (presentation mode), 0.75 to 4
//   slide N                        a deck's slide N (1-based; voxlab view --deck)
//   size WIDTH HEIGHT              window size in pixels
//   wait N                         render N frames
//   screenshot PATH                save the window as PNG
//   quit
//
// Every command's argument count and number formats are checked when the
// script is read; errors are one line, "FILE:LINE: rotate: expected 2 numbers".
#pragma once

#include <string>
#include <vector>

#include "voxlab/camera.h"

namespace voxlab {

struct ViewerStep {
    std::string command;
    std::vector<std::string> args;
    int line = 0;      // 1-based line in the script
    std::string file;  // the script's path as given, for messages
};

// Reads and checks a script; throws voxlab::Error naming FILE:LINE.
std::vector<ViewerStep> parseViewerScript(const std::string& path);
// The same for a script's text; `name` stands for the file in messages and
// its folder anchors relative paths (dataPath).
std::vector<ViewerStep> parseViewerScriptText(const std::string& text, const std::string& name);

// "FILE:LINE", and an Error "FILE:LINE: COMMAND: message" for the executor's
// own failures (a dataset that does not load, an unknown renderer, ...).
std::string stepLocation(const ViewerStep& step);
[[noreturn]] void failStep(const ViewerStep& step, const std::string& message);

// Typed access to argument i (0-based); each throws a located Error when the
// argument is missing or of another kind (parsing already checked the kinds).
const std::string& word(const ViewerStep& step, int i);
double number(const ViewerStep& step, int i);  // "true"/"false" read as 1/0 (param values)
int integer(const ViewerStep& step, int i);
bool onOff(const ViewerStep& step, int i);  // "on" or "off"
// A data file named by argument i, found like the CLI does (resolveDataPath),
// also looking in the script's folder.
std::string dataPath(const ViewerStep& step, int i);

// The panels of `panel NAME on|off` (the transfer-function panel by either
// function's short name), and the same as a list for messages: "slices, tf,
// ... help or controls".
const std::vector<std::string>& viewerPanels();
std::string viewerPanelList();

// Applies a "camera" step's settings, in order, to a camera. Setting azimuth
// or elevation leaves an axis view for the equivalent orbit first; "view"
// sets only the view (pan and zoom are kept).
void applyCameraStep(const ViewerStep& step, CameraSpec* camera);

}  // namespace voxlab
