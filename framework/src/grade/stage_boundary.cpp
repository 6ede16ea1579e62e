// voxlab grader internals: the graded stage's boundary (see stage_boundary.h).
#include "stage_boundary.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "voxlab/project_root.h"
#include "voxlab/renderer.h"
#include "voxlab/stage_registry.h"

namespace voxlab::grading {

namespace {

namespace fs = std::filesystem;

// A name in a GLSL file, where it is (1-based line and column).
struct Use {
    std::string name;
    int line = 0, column = 0;
};

// What one GLSL file names: #include targets, identifiers directly followed
// by '(' (calls, definitions, constructors), the functions it defines (an
// identifier after a type, followed by '(', outside any braces; macros
// too), and the first `##`.
struct GlslScan {
    std::vector<Use> includes, calls;
    std::set<std::string> defined;
    Use paste;
};

bool identStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool identChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Reads the scanner's input one character at a time, keeping the position.
class Cursor {
public:
    explicit Cursor(const std::string& text) : text_(text) {}
    bool done() const { return at_ >= text_.size(); }
    char peek(std::size_t ahead = 0) const { return at_ + ahead < text_.size() ? text_[at_ + ahead] : '\0'; }
    void next() {
        if (text_[at_++] == '\n') ++line_, column_ = 1;
        else ++column_;
    }
    // Skips a comment that starts here; returns whether there was one.
    bool skipComment() {
        if (peek() != '/' || (peek(1) != '/' && peek(1) != '*')) return false;
        if (peek(1) == '/') {
            while (!done() && peek() != '\n') next();
            return true;
        }
        next(), next();
        while (!done() && !(peek() == '*' && peek(1) == '/')) next();
        if (!done()) next(), next();
        return true;
    }
    std::string word() {
        const std::size_t start = at_;
        while (!done() && identChar(peek())) next();
        return text_.substr(start, at_ - start);
    }
    // The next character that is not blank (spaces, tabs, line ends), not consumed.
    char nextSolid() const {
        std::size_t i = at_;
        while (i < text_.size() && (text_[i] == ' ' || text_[i] == '\t' || text_[i] == '\r' || text_[i] == '\n')) ++i;
        return i < text_.size() ? text_[i] : '\0';
    }
    int line() const { return line_; }
    int column() const { return column_; }

private:
    const std::string& text_;
    std::size_t at_ = 0;
    int line_ = 1, column_ = 1;
};

// After '#' at the start of a line: an #include "name" is recorded.
void scanDirective(Cursor& c, GlslScan& scan) {
    c.next();
    while (c.peek() == ' ' || c.peek() == '\t') c.next();
    if (c.word() != "include") return;
    while (c.peek() == ' ' || c.peek() == '\t') c.next();
    if (c.peek() != '"') return;
    c.next();
    Use use{"", c.line(), c.column()};
    while (!c.done() && c.peek() != '"' && c.peek() != '\n') use.name += c.peek(), c.next();
    scan.includes.push_back(use);
}

GlslScan scanGlsl(const std::string& text) {
    GlslScan scan;
    Cursor c(text);
    int depth = 0;
    bool lineStart = true, afterIdent = false;
    while (!c.done()) {
        if (c.skipComment()) continue;
        const char ch = c.peek();
        if (ch == '#' && c.peek(1) == '#' && scan.paste.line == 0) scan.paste = {"##", c.line(), c.column()};
        if (ch == '#' && lineStart) {
            scanDirective(c, scan);
            lineStart = afterIdent = false;
            continue;
        }
        if (identStart(ch)) {
            const Use use{"", c.line(), c.column()};
            const std::string name = c.word();
            if (c.nextSolid() == '(') {
                scan.calls.push_back({name, use.line, use.column});
                if (depth == 0 && afterIdent) scan.defined.insert(name);
            }
            afterIdent = true;
            lineStart = false;
            continue;
        }
        if (ch == '{') ++depth;
        if (ch == '}') depth = std::max(0, depth - 1);
        if (ch == '\n') lineStart = true;
        else if (ch != ' ' && ch != '\t' && ch != '\r') lineStart = false;
        if (ch != ' ' && ch != '\t' && ch != '\r' && ch != '\n') afterIdent = false;
        c.next();
    }
    return scan;
}

bool isGlsl(const fs::path& p) { return isShaderFile(p.string()); }

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The functions each file of `folder` (not recursive) defines.
std::set<std::string> definedIn(const fs::path& folder) {
    std::set<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(folder, ec))
        if (e.is_regular_file(ec) && isGlsl(e.path())) names.merge(scanGlsl(readText(e.path())).defined);
    return names;
}

// The stage folders of the reference (those with a manifest).
std::vector<std::string> stageNames(const std::string& referenceRoot) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(referenceRoot, ec))
        if (fs::exists(e.path() / "grading.json", ec)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string located(const std::string& file, const Use& use) {
    return file + ":" + std::to_string(use.line) + ":" + std::to_string(use.column) + ": ";
}

}  // namespace

std::vector<std::string> requiredStages(const std::string& referenceRoot, const std::string& stage) {
    std::vector<std::string> found, todo = {stage};
    while (!todo.empty()) {
        const std::string next = todo.back();
        todo.pop_back();
        std::ifstream in(fs::path(referenceRoot) / next / "grading.json");
        const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        if (j.is_discarded() || !j.contains("requires") || !j["requires"].is_array()) continue;
        for (const nlohmann::json& r : j["requires"]) {
            if (!r.is_string()) continue;
            const std::string name = r.get<std::string>();
            if (name == stage || std::find(found.begin(), found.end(), name) != found.end()) continue;
            found.push_back(name);
            todo.push_back(name);
        }
    }
    std::sort(found.begin(), found.end());
    return found;
}

std::vector<std::string> frameworkStages(const std::string& referenceRoot) {
    const std::vector<std::string> stages = stageNames(referenceRoot);
    std::set<std::string> found;
    auto addIncluded = [&](const std::string& glsl) {
        for (const Use& include : scanGlsl(glsl).includes) {
            const std::string top = include.name.substr(0, include.name.find('/'));
            if (std::binary_search(stages.begin(), stages.end(), top)) found.insert(top);
        }
    };
    std::error_code ec;
    for (const char* part : {"voxlab", "renderers"})
        for (const auto& e : fs::directory_iterator(fs::path(projectRoot()) / "shaders" / part, ec))
            if (e.is_regular_file(ec)) addIncluded(readText(e.path()));
    // The stages' entry shaders and precomputation passes (their probes each
    // include their own stage only).
    for (const auto& e : fs::recursive_directory_iterator(stagesRoot(), ec)) {
        const std::string file = e.path().filename().string();
        const bool probe = file.size() > 11 && file.compare(file.size() - 11, 11, "_probe.frag") == 0;
        if (e.is_regular_file(ec) && isGlsl(e.path()) && !probe) addIncluded(readText(e.path()));
    }
    // The shaders renderers make from a template, which names its stage by a
    // placeholder (ray_value.frag.in).
    for (const auto& renderer : rendererRegistry().all())
        for (const auto& [name, glsl] : renderer->generatedShaders()) addIncluded(glsl);
    return {found.begin(), found.end()};
}

std::string checkStageBoundary(const std::string& impl, const std::string& stage,
                               const std::vector<std::string>& allowed, const std::string& referenceRoot,
                               const std::string& shadersRoot) {
    const fs::path own = fs::path(impl) / stage;
    std::vector<std::pair<std::string, GlslScan>> files;
    std::set<std::string> mayCall;  // what it defines itself, or a stage it may use defines
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(own, ec))
        if (e.is_regular_file(ec) && isGlsl(e.path())) {
            files.push_back({stage + "/" + e.path().filename().string(), scanGlsl(readText(e.path()))});
            mayCall.insert(files.back().second.defined.begin(), files.back().second.defined.end());
        }
    std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const std::string& s : allowed) mayCall.merge(definedIn(fs::path(referenceRoot) / s));
    mayCall.merge(definedIn(fs::path(shadersRoot) / "voxlab"));
    std::map<std::string, std::string> foreign;  // function -> the stage that alone defines it
    const std::vector<std::string> stages = stageNames(referenceRoot);
    for (const std::string& s : stages) {
        if (s == stage || std::count(allowed.begin(), allowed.end(), s)) continue;
        for (const std::string& name : definedIn(fs::path(referenceRoot) / s))
            if (!mayCall.count(name)) foreign.emplace(name, s);
    }
    const std::string uses = allowed.empty() ? "no other stage" : "only the stages in its grading.json \"requires\"";
    for (const auto& [file, scan] : files) {
        if (scan.paste.line > 0)
            return located(file, scan.paste) + "token pasting (##) is not allowed in a graded stage's files";
        for (const Use& include : scan.includes) {
            const std::string top = include.name.substr(0, include.name.find('/'));
            if (top != stage && std::binary_search(stages.begin(), stages.end(), top) &&
                !std::count(allowed.begin(), allowed.end(), top))
                return located(file, include) + "'" + include.name + "' is stage " + top + "'s file: " + stage +
                       " may use " + uses + ", so it cannot include it";
        }
        for (const Use& call : scan.calls)
            if (const auto f = foreign.find(call.name); f != foreign.end())
                return located(file, call) + call.name + "() belongs to stage " + f->second + ", and " + stage +
                       " may use " + uses + ": write what you need yourself";
    }
    return "";
}

}  // namespace voxlab::grading
