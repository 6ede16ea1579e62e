// voxlab viewer: saying which functions the checkerboard stands for.
//
// A student's first picture is the magenta-and-black checkerboard of the
// starter code's stubs (shaders/voxlab/not_implemented.glsl). The picture
// alone does not say what is missing, so after each full-quality render the
// line of missingFunctionsNotice (grading.h) is shown over the image and,
// when it changes, printed to the terminal.
#include <cstdio>

#include "viewer_state.h"
#include "voxlab/grading.h"

namespace voxlab::viewer {

void updateStubNotice(State& s) {
    if (!s.main.engine) return;
    const std::string notice = missingFunctionsNotice(*s.main.engine);
    if (!notice.empty() && notice != s.stubNotice) std::fprintf(stderr, "voxlab: %s\n", notice.c_str());
    s.stubNotice = notice;
}

}  // namespace voxlab::viewer
