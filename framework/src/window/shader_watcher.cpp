// voxlab viewer: live reload of shader files (see viewer_state.h).
#include <sys/stat.h>

#include "viewer_state.h"

namespace voxlab::viewer {

bool ShaderWatcher::changed(const std::vector<std::string>& files) {
    const Clock::time_point now = Clock::now();
    if (now - lastCheck_ < std::chrono::milliseconds(500)) return false;
    lastCheck_ = now;
    bool any = false;
    for (const std::string& file : files) {
        struct stat st;
        // A file being replaced (editors save by rename) may be missing for
        // a moment: keep its old stamp and look again next time.
        if (stat(file.c_str(), &st) != 0) continue;
        const long long stamp = (long long)st.st_mtim.tv_sec * 1000000000LL + st.st_mtim.tv_nsec;
        auto [it, inserted] = stamps_.try_emplace(file, stamp);
        if (!inserted && it->second != stamp) {
            it->second = stamp;
            any = true;
        }
    }
    return any;
}

}  // namespace voxlab::viewer
