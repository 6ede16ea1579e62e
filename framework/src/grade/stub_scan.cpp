// voxlab: finding the starter code's stubs left in a stage (see grading.h).
//
// tools/make_assignments.py replaces each solution body with a stub that
// calls not_implemented() (GLSL) or throws NotImplemented (C++). A function
// whose body still holds that call is reported by name, so that a student
// reads "mip_ray is not yet implemented" rather than a failed image.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>

#include "voxlab/grading.h"
#include "voxlab/render_engine.h"

namespace voxlab {

namespace {

// The name of the function whose signature starts at column 0 above `line`.
std::string enclosingFunction(const std::vector<std::string>& lines, std::size_t line) {
    static const std::regex signature(R"(^[A-Za-z_][\w:<>,\s\*&]*?\b(\w+)\s*\()");
    for (std::size_t k = line + 1; k-- > 0;) {
        const std::string& l = lines[k];
        if (l.empty() || std::isspace(static_cast<unsigned char>(l[0])) || l.rfind("//", 0) == 0 || l[0] == '#')
            continue;
        std::smatch m;
        if (std::regex_search(l, m, signature)) return m[1];
    }
    return "";
}

}  // namespace

std::vector<std::string> unimplementedFunctions(const std::string& stageFolder) {
    namespace fs = std::filesystem;
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(stageFolder, ec)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".glsl" || ext == ".frag" || ext == ".vert" || ext == ".cpp"))
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    static const std::regex stubCall(R"(^\s*(not_implemented\s*\(\s*\)\s*;|throw\s+NotImplemented\s*\())");
    std::vector<std::string> names;
    for (const fs::path& file : files) {
        std::ifstream in(file);
        std::vector<std::string> lines;
        for (std::string l; std::getline(in, l);) lines.push_back(l);
        for (std::size_t i = 0; i < lines.size(); ++i) {
            if (!std::regex_search(lines[i], stubCall)) continue;
            const std::string name = enclosingFunction(lines, i);
            if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        }
    }
    return names;
}

namespace {

// The stage folders (root/<stage>/) of the files under `root`, in order.
std::vector<std::filesystem::path> stageFolders(const std::vector<std::string>& files,
                                                const std::filesystem::path& root) {
    namespace fs = std::filesystem;
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

std::string missingFunctionsNotice(const RenderEngine& engine) {
    const std::filesystem::path root = std::filesystem::absolute(engine.implementationRoot()).lexically_normal();
    std::string missing;
    for (const std::filesystem::path& folder : stageFolders(engine.lastRenderSources(), root)) {
        const std::vector<std::string> names = unimplementedFunctions(folder.string());
        if (names.empty()) continue;
        std::string list;
        for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n + "()";
        missing += (missing.empty() ? "" : "; ") + folder.filename().string() + "/: " + list;
    }
    return missing.empty() ? ""
                           : "not yet implemented: " + missing +
                                 " (the magenta checkerboard marks where a ray reaches one). Run `voxlab check` for every stage.";
}

}  // namespace voxlab
