// voxlab: finding the starter code's stubs left in a stage (see grading.h).
//
// tools/make_assignments.py replaces each solution body with a stub that
// calls not_implemented() (GLSL) or throws NotImplemented (C++). A function
// whose body still holds that call is reported by name, so that a student
// reads "mip_ray is not yet implemented" rather than a failed image.
#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "../io/line_scan.h"
#include "voxlab/grading.h"
#include "voxlab/render_engine.h"

namespace voxlab {

namespace {

// A character a signature may hold before the function's name: a return
// type such as "std::vector<glm::vec3>", "const float*" or "int&".
bool inSignature(char c) { return scan::isWord(c) || scan::isSpace(c) || std::strchr(":<>,*&", c); }

// The function's name in a line that starts a signature ("float mip_ray(",
// "std::vector<glm::vec3> planeBoxPolygon("): the first word, after the
// line's first character and before any character a signature cannot hold,
// that is followed by '(' (spaces allowed between). "" when there is none.
std::string signatureName(const std::string& line) {
    if (line.empty() || !(std::isalpha(static_cast<unsigned char>(line[0])) || line[0] == '_') ||
        static_cast<unsigned char>(line[0]) >= 0x80)
        return "";
    for (std::size_t k = 1; k < line.size() && inSignature(line[k - 1]); ++k) {
        if (!scan::isWord(line[k]) || scan::isWord(line[k - 1])) continue;  // not the start of a word
        scan::Line l{line, k};
        std::string name;
        l.identifier(&name);
        l.spaces();
        if (l.literal("(")) return name;
    }
    return "";
}

// The name of the function whose signature starts at column 0 above `line`.
std::string enclosingFunction(const std::vector<std::string>& lines, std::size_t line) {
    for (std::size_t k = line + 1; k-- > 0;) {
        const std::string& l = lines[k];
        if (l.empty() || std::isspace(static_cast<unsigned char>(l[0])) || l.rfind("//", 0) == 0 || l[0] == '#')
            continue;
        const std::string name = signatureName(l);
        if (!name.empty()) return name;
    }
    return "";
}

// Whether a line starts (after spaces) with the starter code's stub:
// "not_implemented();" (GLSL) or "throw NotImplemented(" (C++).
bool isStubCall(const std::string& line) {
    scan::Line l{line};
    l.spaces();
    if (l.literal("not_implemented")) {
        l.spaces();
        if (!l.literal("(")) return false;
        l.spaces();
        if (!l.literal(")")) return false;
        l.spaces();
        return l.literal(";");
    }
    return l.literal("throw") && l.spaces() && l.literal("NotImplemented") && (l.spaces(), l.literal("("));
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
    std::vector<std::string> names;
    for (const fs::path& file : files) {
        std::ifstream in(file);
        std::vector<std::string> lines;
        for (std::string l; std::getline(in, l);) lines.push_back(l);
        for (std::size_t i = 0; i < lines.size(); ++i) {
            if (!isStubCall(lines[i])) continue;
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
