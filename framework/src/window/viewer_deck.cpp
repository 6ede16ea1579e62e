// voxlab viewer: stepping through a demo deck (voxlab/deck.h).
//
// A slide replaces the whole scene (renderer, parameters, transfer
// functions, camera); the volume is loaded again only when the slide's
// dataset differs from the one shown. The caption is drawn by the overlays
// (viewer_panels.cpp).
#include <algorithm>
#include <cstdio>

#include "viewer_state.h"

namespace voxlab::viewer {

void showSlide(State& s, int index) {
    if (!s.deck) return;
    const int n = int(s.deck->slides.size());
    index = std::clamp(index, 0, n - 1);
    const Slide& slide = s.deck->slides[std::size_t(index)];
    setScene(s, slide.scene, s.scenePath);
    s.slide = index;
    s.selectedPoint = s.selectedWidget = -1;
    // In the terminal too: a script (and its test) sees which slide is up.
    std::printf("slide %d/%d: %s%s%s\n", index + 1, n, slide.scene.renderer.c_str(), slide.caption.empty() ? "" : ": ",
                slide.caption.c_str());
    std::fflush(stdout);
}

}  // namespace voxlab::viewer
