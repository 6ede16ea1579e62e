// voxlab viewer: saying which functions the checkerboard stands for.
//
// A student's first picture is the magenta-and-black checkerboard of the
// starter code's stubs (shaders/voxlab/not_implemented.glsl). The picture
// alone does not say what is missing, so after each full-quality render the
// stage folders of the shader files that render used (those inside the left
// side's implementation) are scanned for stubs, as the grader does
// (unimplementedFunctions, grading.h). The result is one line, shown over the
// image and printed once to the terminal.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "viewer_state.h"
#include "voxlab/grading.h"

namespace voxlab::viewer {

namespace {

namespace fs = std::filesystem;

// The stage folders (root/<stage>/) of the files under `root`, in order.
std::vector<fs::path> stageFolders(const std::vector<std::string>& files, const fs::path& root) {
    std::vector<fs::path> folders;
    for (const std::string& f : files) {
        const fs::path rel = fs::absolute(f).lexically_normal().lexically_relative(root);
        if (rel.empty() || *rel.begin() == "..") continue;
        const fs::path folder = root / *rel.begin();
        if (fs::is_directory(folder) && std::find(folders.begin(), folders.end(), folder) == folders.end())
            folders.push_back(folder);
    }
    return folders;
}

}  // namespace

void updateStubNotice(State& s) {
    if (!s.main.engine) return;
    const fs::path root = fs::absolute(s.main.engine->implementationRoot()).lexically_normal();
    std::string missing;
    for (const fs::path& folder : stageFolders(s.main.engine->lastRenderSources(), root)) {
        const std::vector<std::string> names = unimplementedFunctions(folder.string());
        if (names.empty()) continue;
        std::string list;
        for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n + "()";
        missing += (missing.empty() ? "" : "; ") + folder.filename().string() + "/: " + list;
    }
    const std::string notice =
        missing.empty() ? "" : "checkerboard = not yet implemented: " + missing + ". Run `voxlab check` for every stage.";
    if (!notice.empty() && notice != s.stubNotice) std::fprintf(stderr, "voxlab: %s\n", notice.c_str());
    s.stubNotice = notice;
}

}  // namespace voxlab::viewer
