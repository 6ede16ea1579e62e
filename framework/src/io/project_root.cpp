// voxlab: the project's root folder (voxlab/project_root.h).
#include "voxlab/project_root.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#ifndef VOXLAB_SOURCE_DIR
#define VOXLAB_SOURCE_DIR "."
#endif

namespace voxlab {

namespace fs = std::filesystem;

namespace {

// A folder is a root when it has the shader library every program includes.
bool isRoot(const fs::path& folder) {
    std::error_code ec;
    return fs::is_regular_file(folder / "shaders" / "voxlab" / "ray.glsl", ec);
}

// The root found from /proc/self/exe, or "" (no /proc, or no root near it).
std::string rootBesideExecutable() {
    char buffer[4096];
    const ssize_t n = ::readlink("/proc/self/exe", buffer, sizeof buffer - 1);
    if (n <= 0) return "";
    fs::path folder = fs::path(std::string(buffer, std::size_t(n))).parent_path();
    for (int level = 0; level < 4 && !folder.empty(); ++level) {
        if (isRoot(folder / "share" / "voxlab")) return (folder / "share" / "voxlab").string();
        if (isRoot(folder)) return folder.string();
        if (folder == folder.root_path()) break;
        folder = folder.parent_path();
    }
    return "";
}

}  // namespace

std::string projectRoot() {
    if (const char* root = std::getenv("VOXLAB_ROOT"); root && *root) return root;
    static const std::string found = [] {
        const std::string beside = rootBesideExecutable();
        return beside.empty() ? std::string(VOXLAB_SOURCE_DIR) : beside;
    }();
    return found;
}

std::string stagesRoot() { return projectRoot() + "/framework/stages"; }

std::vector<std::string> frameworkShaderFolders() { return {projectRoot() + "/shaders", stagesRoot()}; }

bool isShaderFile(const std::string& path) {
    const std::string ext = fs::path(path).extension().string();
    return ext == ".glsl" || ext == ".frag" || ext == ".vert";
}

}  // namespace voxlab
