// voxlab viewer: saying which functions the checkerboard stands for.
//
// A student's first picture is the magenta-and-black checkerboard of the
// starter code's stubs (shaders/voxlab/not_implemented.glsl). The picture
// alone does not say what is missing, so after each full-quality render that
// shows the checkerboard the line of missingFunctionsNotice (stub_text.h) is
// shown over the image and, when it changes, printed to the terminal.
#include <cstdio>

#include "viewer_state.h"
#include "voxlab/stub_text.h"
#include "voxlab/stubs_reached.h"
#include "voxlab/error.h"
#include "voxlab/image.h"

namespace voxlab::viewer {

void updateStubNotice(State& s, const Scene& scene) {
    if (!s.main.engine) return;
    // Only while the checkerboard is on screen, naming the stubs its pixels
    // reached (drawn again at up to 256 pixels a side, into a target of the
    // engine's own): a stub compiled in but never run, such as sampling's
    // under hardware filtering or cubic's under trilinear, is not named.
    // Reading the image back costs a few ms, and only a starter's stubs pay it.
    std::string notice;
    if (!s.main.engine->lastRenderStubs().empty() && s.main.error.empty()) {
        try {
            notice = missingFunctionsNotice(stubsReached(*s.main.engine, scene, s.main.engine->readBack(), 256));
        } catch (const Error& e) {
            notice = missingFunctionsNotice(s.main.engine->lastRenderStubs());
        }
    }
    if (!notice.empty() && notice != s.stubNotice) std::fprintf(stderr, "voxlab: %s\n", notice.c_str());
    s.stubNotice = notice;
}

}  // namespace voxlab::viewer
