// voxlab: demo decks, the scenes a lecturer steps through in the viewer
// (`voxlab view --deck FILE`, arrow keys or Page Up/Down).
//
// A deck is a JSON file:
//
//   {
//     "title": "Lecture 4: direct volume rendering",      (optional)
//     "slides": [
//       {"scene": "scenes/bonsai_mip.json", "caption": "MIP: the brightest sample"},
//       {"scene": "scenes/bonsai_mip.json", "transfer_function": "tf/bonsai.json",
//        "caption": "MIP through a transfer function"},
//       {"scene": {"dataset": "tooth.nrrd", "renderer": "iso"}, "caption": "an isosurface"}
//     ]
//   }
//
// Each slide is a scene: a scene file (relative to the deck's folder) or a
// scene written inline, in the scene-file format (scene.h). Any other key
// of the slide is a scene key that replaces the scene's own (renderer,
// parameters, camera, transfer_function, transfer_function_2d, window,
// sampling, ...), so one scene can serve several slides. "caption" is the
// line shown under the image. Relative paths inside a slide resolve like a
// scene's: against the scene file's folder (the deck's for an inline
// scene), then the data path.
//
// Errors are one line that names the deck and the slide:
// "talk.json: slide 3: camera.azimuth: expected a number". (Renderer names
// are checked by the viewer before its window opens.)
#pragma once

#include <string>
#include <vector>

#include "voxlab/scene.h"

namespace voxlab {

struct Slide {
    Scene scene;
    std::string caption;
};

struct Deck {
    std::string title;
    std::vector<Slide> slides;  // at least one
};

// Limits: a deck of more than this many slides is refused (a lecture has
// tens, not thousands; each slide keeps its scene in memory).
constexpr int kMaxSlides = 500;

Deck loadDeck(const std::string& path);

}  // namespace voxlab
