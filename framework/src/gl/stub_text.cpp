// voxlab: finding the starter code's stubs in a stage's text
// (voxlab/stub_text.h).
//
// tools/make_assignments.py replaces each solution body with a stub that
// calls not_implemented() (GLSL) or throws NotImplemented (C++). A function
// whose body still holds that call is reported by name, so that a student
// reads "mip_ray is not yet implemented" rather than a failed image.
#include "voxlab/stub_text.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "../io/line_scan.h"

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

namespace {

std::vector<std::string> fileLines(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

bool isStageSource(const std::filesystem::path& file) {
    const std::string ext = file.extension().string();
    return ext == ".glsl" || ext == ".frag" || ext == ".vert" || ext == ".cpp";
}

}  // namespace

std::string stubCallFunction(const std::vector<std::string>& lines, std::size_t i) {
    if (i >= lines.size()) return "";
    scan::Line l{lines[i]};
    l.spaces();
    if (!l.literal("not_implemented")) return "";  // the GLSL form only
    return isStubCall(lines[i]) ? enclosingFunction(lines, i) : "";
}

std::vector<std::string> unimplementedFunctions(const std::string& stageFolder) {
    namespace fs = std::filesystem;
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(stageFolder, ec))
        if (entry.is_regular_file() && isStageSource(entry.path())) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    std::vector<std::string> names;
    for (const fs::path& file : files) {
        const std::vector<std::string> lines = fileLines(file);
        for (std::size_t i = 0; i < lines.size(); ++i) {
            if (!isStubCall(lines[i])) continue;
            const std::string name = enclosingFunction(lines, i);
            if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        }
    }
    return names;
}

std::string stubListText(const std::vector<std::string>& stubs) {
    std::vector<std::string> stages;  // in the order they first appear
    for (const std::string& s : stubs)
        if (!std::count(stages.begin(), stages.end(), s.substr(0, s.find('/')))) stages.push_back(s.substr(0, s.find('/')));
    std::string text;
    for (const std::string& stage : stages) {
        std::string functions;
        for (const std::string& s : stubs)
            if (s.substr(0, s.find('/')) == stage) functions += (functions.empty() ? "" : ", ") + s.substr(s.find('/') + 1) + "()";
        text += (text.empty() ? "" : "; ") + stage + "/: " + functions;
    }
    return text;
}

std::string missingFunctionsNotice(const std::vector<std::string>& stubs) {
    if (stubs.empty()) return "";
    return "not yet implemented: " + stubListText(stubs) +
           " (the magenta checkerboard marks where a ray reaches one). Run `voxlab check` for every stage.";
}

}  // namespace voxlab
