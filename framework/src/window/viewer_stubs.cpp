// voxlab viewer: saying which functions the checkerboard stands for.
//
// A student's first picture is the magenta-and-black checkerboard of the
// starter code's stubs (shaders/voxlab/not_implemented.glsl). The picture
// alone does not say what is missing, so after each full-quality render the
// line of missingFunctionsNotice (grading.h) is shown over the image and,
// when it changes, printed to the terminal.
#include <cstdio>
#include <filesystem>

#include "viewer_state.h"
#include "voxlab/grading.h"

namespace voxlab::viewer {

void updateStubNotice(State& s) {
    if (!s.main.engine) return;
    // Scanned again only when the render used other files, or one of them
    // was saved since: a slider dragged at full quality renders every frame.
    std::string key = s.main.engine->implementationRoot();
    for (const std::string& f : s.main.engine->lastRenderSources()) {
        std::error_code ec;
        const auto stamp = std::filesystem::last_write_time(f, ec);
        key += "\n" + f + " " + std::to_string(ec ? 0LL : (long long)stamp.time_since_epoch().count());
    }
    if (key == s.stubKey) return;
    s.stubKey = key;
    const std::string notice = missingFunctionsNotice(*s.main.engine);
    if (!notice.empty() && notice != s.stubNotice) std::fprintf(stderr, "voxlab: %s\n", notice.c_str());
    s.stubNotice = notice;
}

}  // namespace voxlab::viewer
