// voxlab: GLSL preprocessing (#include with a search path), compilation and
// error mapping. See shader.h.
#include "voxlab/shader.h"

#include <filesystem>

#include <algorithm>
#include <fstream>
#include <cstring>
#include <set>
#include <sstream>
#include <sys/stat.h>

#include "../io/line_scan.h"
#include "voxlab/gl_context.h"
#include "voxlab/stub_text.h"
#include "voxlab/project_root.h"
#include "voxlab_gl.h"

namespace voxlab {
namespace {

bool isFile(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ShaderError(path + ": cannot read shader file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Shows paths relative to the project root when they are inside it.
std::string displayPath(const std::string& path) {
    const std::string root = projectRoot() + "/";
    return path.compare(0, root.size(), root) == 0 ? path.substr(root.size()) : path;
}

// Parses `#include "name"` (spaces anywhere between, a // comment after);
// returns false for any other line.
bool parseInclude(const std::string& line, std::string* name) {
    scan::Line l{line};
    l.spaces();
    if (!l.literal("#")) return false;
    l.spaces();
    if (!l.literal("include")) return false;
    l.spaces();
    if (!l.literal("\"")) return false;
    const std::size_t close = line.find('"', l.at);
    if (close == std::string::npos || close == l.at) return false;
    const std::string inside = line.substr(l.at, close - l.at);
    l.at = close + 1;
    if (!l.commentOrEnd()) return false;
    *name = inside;
    return true;
}

// Mesa honours the line number of `#line L S` but not the source number S
// in its logs, so each file's lines are numbered from fileId * kLineStride:
// a reported line L means file L / kLineStride, line L % kLineStride.
constexpr int kLineStride = 100000;

std::string lineDirective(int fileId, int line) {
    return "#line " + std::to_string(fileId * kLineStride + line) + "\n";
}

// `uniform int NAME;` (or bool), for baking a uniform into a constant.
bool parseIntUniform(const std::string& line, std::string* name) {
    scan::Line l{line};
    l.spaces();
    if (!l.literal("uniform") || !l.spaces() || !(l.literal("int") || l.literal("bool")) || !l.spaces()) return false;
    std::string id;
    if (!l.identifier(&id)) return false;
    l.spaces();
    if (!l.literal(";") || !l.commentOrEnd()) return false;
    *name = id;
    return true;
}

// `#version 330` or `#version 330 core`, with an optional // comment.
bool isVersion330(const std::string& line) {
    scan::Line l{line};
    l.spaces();
    if (!l.literal("#")) return false;
    l.spaces();
    if (!l.literal("version") || !l.spaces() || !l.literal("330")) return false;
    const std::size_t afterNumber = l.at;
    if (!(l.spaces() && l.literal("core"))) l.at = afterNumber;
    return l.commentOrEnd(true);
}

// Whether `text` declares `void main()` (or `void main(void)`) anywhere.
bool declaresMain(const std::string& text) {
    for (std::size_t at = text.find("void"); at != std::string::npos; at = text.find("void", at + 1)) {
        if (at > 0 && scan::isWord(text[at - 1])) continue;
        scan::Line l{text, at + 4};
        if (!l.spaces() || !l.literal("main")) continue;
        l.spaces();
        if (!l.literal("(")) continue;
        l.spaces();
        const std::size_t beforeVoid = l.at;
        if (!(l.literal("void") && (l.spaces(), l.literal(")")))) {
            l.at = beforeVoid;
            if (!l.literal(")")) continue;
        }
        return true;
    }
    return false;
}

}  // namespace

GlslDialect nativeGlslDialect() {
#ifdef __EMSCRIPTEN__
    return GlslDialect::Es300;
#else
    return GlslDialect::Core330;
#endif
}

std::string versionPreamble(const std::string& firstLine, GlslDialect dialect, const std::string& where) {
    if (!isVersion330(firstLine))
        throw ShaderError(where + ": an entry shader's first line is '#version 330 core' (found '" +
                          firstLine.substr(0, 60) + "')");
    if (dialect == GlslDialect::Core330) return "#version 330 core\n";
    // ES has no default precision for float in fragment shaders nor for any
    // sampler type; highp everywhere is what the core profile means.
    std::string text = "#version 300 es\nprecision highp float;\nprecision highp int;\n";
    for (const char* sampler : {"sampler2D", "sampler3D", "isampler2D", "isampler3D", "usampler2D",
                                "usampler3D", "sampler2DArray", "samplerCube"})
        text += std::string("precision highp ") + sampler + ";\n";
    return text;
}

namespace {

struct Preprocessor {
    const ShaderLibrary& lib;
    const ShaderConstants& constants;
    PreprocessedShader out;
    std::set<std::string> included;
    std::vector<std::string> stack;

    void addFile(const std::string& path, bool isEntry) {
        if (included.count(path)) return;  // each library once per program
        if (std::find(stack.begin(), stack.end(), path) != stack.end())
            throw ShaderError(displayPath(path) + ": circular #include");
        included.insert(path);
        stack.push_back(path);
        const int fileId = int(out.files.size());
        out.files.push_back(displayPath(path));

        const std::string* generated = lib.generatedText(path);
        std::istringstream in(generated ? *generated : readText(path));
        std::string line;
        std::vector<std::string> lines;  // this file's, for the function a stub's call is in
        int lineNo = 0;
        if (!isEntry) out.text += lineDirective(fileId, 1);
        while (std::getline(in, line)) {
            ++lineNo;
            lines.push_back(line);
            std::string name;
            const std::string stub = stubCallFunction(lines, lines.size() - 1);
            if (!stub.empty()) {  // numbered: the render can say which stubs it reached
                out.text += "not_implemented_at(" + std::to_string(stubNumber(path, stub)) + ");\n";
                continue;
            }
            if (lineNo == 1 && isEntry) {
                // `#version` must come first; everything after it is
                // numbered from line 2 of file 0.
                out.text += versionPreamble(line, lib.dialect(), displayPath(path) + ":1") + lineDirective(fileId, 2);
                continue;
            }
            if (parseInclude(line, &name)) {
                for (const std::string& file : lib.resolveAll(name, displayPath(path) + ":" + std::to_string(lineNo)))
                    addFile(file, false);
                out.text += lineDirective(fileId, lineNo + 1);
            } else if (parseIntUniform(line, &name) && constants.count(name)) {
                // Baked: same line count, so error lines still map.
                out.text += "const int " + name + " = " + std::to_string(constants.at(name)) + ";\n";
            } else {
                out.text += line + "\n";
            }
        }
        stack.pop_back();
    }

    // The number of the stub "stage/function" (the file's folder), from 0;
    // past the last number a float holds exactly as a set of bits, the last.
    int stubNumber(const std::string& path, const std::string& function) {
        const std::string name = std::filesystem::path(path).parent_path().filename().string() + "/" + function;
        const auto at = std::find(out.stubs.begin(), out.stubs.end(), name);
        if (at != out.stubs.end()) return int(at - out.stubs.begin());
        if (out.stubs.size() < kMaxNumberedStubs) out.stubs.push_back(name);
        return int(out.stubs.size()) - 1;
    }
};

// The info log of a shader or program, as a string without the trailing NUL.
template <class GetIv, class GetLog>
std::string infoLog(GLuint object, GetIv getIv, GetLog getLog) {
    GLint len = 0;
    getIv(object, GL_INFO_LOG_LENGTH, &len);
    std::string log(std::max(len, 1), '\0');
    getLog(object, len, nullptr, &log[0]);
    log.resize(std::strlen(log.c_str()));
    return log;
}

unsigned compileStage(GLenum stage, const PreprocessedShader& src) {
    const GLuint shader = glCreateShader(stage);
    const char* text = src.text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = infoLog(shader, glGetShaderiv, glGetShaderInfoLog);
        glDeleteShader(shader);
        throw ShaderError(src.mapLog(log));
    }
    return shader;
}

// The entry shader's main() renamed voxlab_entry_main and called from a
// main() of ours: `declarations` go before it, `before` and `after` around
// the call. A shader without a main() is left as it is.
PreprocessedShader aroundMain(PreprocessedShader fs, const std::string& declarations, const std::string& before,
                              const std::string& after) {
    const std::size_t firstLine = fs.text.find('\n');
    if (firstLine == std::string::npos || !declaresMain(fs.text)) return fs;
    fs.text.insert(firstLine + 1, "#define main voxlab_entry_main\n");
    fs.text += "\n#undef main\n" + declarations + "void main() {\n" + before + "    voxlab_entry_main();\n" + after +
               "}\n";
    return fs;
}

// llvmpipe, Mesa's software rasterizer, JIT-compiles the fragment shader of
// a draw that neither blends nor can discard ("opaque", lp_state_fs.c) twice:
// once for whole 64x64 tiles, once for tiles that a triangle's edge crosses.
// A shader that may discard is compiled once, and its edge version serves
// every tile. Compiling is most of a grading run's first render of a scene
// (docs/grading.md), so with ShaderLibrary::setCompileOnce on llvmpipe the
// entry shader's main() is renamed and called from a main() whose discard
// never happens: its uniform is never set. Not always: a shader that may
// discard runs a few per cent slower (bonsai MIP at 512², 122 against 117 ms),
// which matters more to the viewer than one compile.
// (Blending src*1 + dst*0 instead was tried: llvmpipe computes it as
// dst + (src - dst), off by one unit in the last place wherever the target
// held something.) Other drivers get the shader as written.
PreprocessedShader compiledOnceOnLlvmpipe(PreprocessedShader fs) {
    return aroundMain(std::move(fs), "uniform bool voxlab_never_set;\n", "    if (voxlab_never_set) discard;\n", "");
}

// The ray profile's record pass (u_profile = 2, voxlab/profile.glsl): the
// entry shader's main() runs as written, then the colour it wrote gives way
// to what the ray library recorded of this fragment's sample. Every entry
// shader of a ray caster writes `frag_color`.
PreprocessedShader withProfileRecord(PreprocessedShader fs) {
    return aroundMain(std::move(fs), "", "", "    frag_color = voxlab_profile_record();\n");
}

}  // namespace

namespace {

// One line of a compiler's log in a format known here: the encoded line
// number (see kLineStride), what follows it, and the message.
struct LogLine {
    long line = 0;
    std::string after;    // ":5" (Mesa's column), or nothing
    std::string message;  // ANGLE's with "error: " or "warning: " in front
};

// Mesa: "0:12(5): error: ...".
bool parseMesaLine(const std::string& text, LogLine* out) {
    *out = LogLine();
    scan::Line l{text};
    if (!l.number(nullptr) || !l.literal(":") || !l.number(&out->line) || !l.literal("(")) return false;
    const std::size_t column = l.at;
    if (!l.number(nullptr)) return false;
    out->after = ":" + text.substr(column, l.at - column);
    if (!l.literal("):")) return false;
    l.spaces();
    return l.restOfLine(&out->message);
}

// NVIDIA: "0(12) : error C0000: ...".
bool parseNvidiaLine(const std::string& text, LogLine* out) {
    *out = LogLine();
    scan::Line l{text};
    if (!l.number(nullptr) || !l.literal("(") || !l.number(&out->line) || !l.literal(")")) return false;
    l.spaces();
    if (!l.literal(":")) return false;
    l.spaces();
    return l.restOfLine(&out->message);
}

// ANGLE (WebGL in Chromium) and glslang: "ERROR: 0:12: 'x' : undeclared identifier".
bool parseAngleLine(const std::string& text, LogLine* out) {
    *out = LogLine();
    scan::Line l{text};
    const bool error = l.literal("ERROR");
    if (!error && !l.literal("WARNING")) return false;
    if (!l.literal(":")) return false;
    l.spaces();
    if (!l.number(nullptr) || !l.literal(":") || !l.number(&out->line) || !l.literal(":")) return false;
    l.spaces();
    if (!l.restOfLine(&out->message)) return false;
    out->message.insert(0, error ? "error: " : "warning: ");
    return true;
}

}  // namespace

std::string PreprocessedShader::mapLog(const std::string& log) const {
    std::istringstream in(log);
    std::string line, result;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        LogLine parsed;
        if (parseMesaLine(line, &parsed) || parseNvidiaLine(line, &parsed) || parseAngleLine(line, &parsed)) {
            const std::size_t id = std::size_t(parsed.line / kLineStride);
            line = (id < files.size() ? files[id] : "<source " + std::to_string(id) + ">") + ":" +
                   std::to_string(parsed.line % kLineStride) + parsed.after + ": " + parsed.message;
        }
        result += (result.empty() ? "" : "\n") + line;
    }
    return result.empty() ? "shader compilation failed with an empty log" : result;
}

ShaderLibrary::ShaderLibrary(std::vector<std::string> searchPath) : searchPath_(std::move(searchPath)) {}

ShaderLibrary ShaderLibrary::forImplementation(const std::string& implementationRoot) {
    const std::string reference = projectRoot() + "/reference";
    std::vector<std::string> path = {implementationRoot};
    if (std::filesystem::is_directory(reference) &&
        std::filesystem::path(implementationRoot).lexically_normal() != std::filesystem::path(reference).lexically_normal())
        path.push_back(reference);
    path.push_back(projectRoot() + "/shaders");
    return ShaderLibrary(path);
}

namespace {

// An include name is a relative path that stays inside the folder it is
// found in: no absolute paths, no "..", no empty or "." parts.
void checkIncludeName(const std::string& name, const std::string& where) {
    bool ok = !name.empty() && name[0] != '/' && name.find('\\') == std::string::npos;
    for (std::size_t start = 0; ok && start <= name.size();) {
        const std::size_t end = std::min(name.find('/', start), name.size());
        const std::string part = name.substr(start, end - start);
        ok = !part.empty() && part != "." && part != "..";
        start = end + 1;
    }
    if (!ok)
        throw ShaderError(where + "shader '" + name +
                          "': an #include names a file inside the implementation or shaders/ folder "
                          "by a relative path without '..'");
}

// The real path of `path` when it lies beneath `dir` (links resolved), else "".
std::string confinedPath(const std::string& dir, const std::string& path) {
    std::error_code ec;
    const std::filesystem::path realDir = std::filesystem::canonical(dir, ec);
    if (ec) return "";
    const std::filesystem::path real = std::filesystem::canonical(path, ec);
    if (ec) return "";
    const std::string prefix = realDir.string() + "/";
    return real.string().compare(0, prefix.size(), prefix) == 0 ? path : "";
}

// Names that only the framework's stage folders answer (voxlab/project_root.h).
const std::string kStagesPrefix = "stages/";

// `folder`/`relative`, which must be a file inside `folder` (links resolved).
std::string resolveIn(const std::string& folder, const std::string& relative, const std::string& name,
                      const std::string& where) {
    const std::string path = folder + "/" + relative;
    if (!isFile(path)) throw ShaderError(where + "shader '" + name + "' not found (searched: " + displayPath(folder) + ")");
    if (confinedPath(folder, path).empty())
        throw ShaderError(where + "shader '" + name + "' leads outside " + displayPath(folder) + " (a link?)");
    return path;
}

}  // namespace

void ShaderLibrary::addGenerated(const std::string& name, const std::string& text) {
    checkIncludeName(name, "");
    generated_["generated:" + name] = text;
}

const std::string* ShaderLibrary::generatedText(const std::string& path) const {
    const auto found = generated_.find(path);
    return found == generated_.end() ? nullptr : &found->second;
}

std::string ShaderLibrary::resolve(const std::string& name, const std::string& includedFrom) const {
    const std::string where = includedFrom.empty() ? "" : includedFrom + ": ";
    checkIncludeName(name, where);
    if (generated_.count("generated:" + name)) return "generated:" + name;
    if (name.rfind(kStagesPrefix, 0) == 0) {
        // A stage folder holds C++ and tests beside its shaders: only these.
        if (!isShaderFile(name)) throw ShaderError(where + "shader '" + name + "': not a .glsl, .frag or .vert file");
        return resolveIn(stagesRoot(), name.substr(kStagesPrefix.size()), name, where);
    }
    // A stage the first folder (the implementation) has is its alone: an
    // empty or incomplete stage folder does not borrow a later folder's files.
    const std::string top = name.substr(0, name.find('/'));
    const bool owned = name.find('/') != std::string::npos && !searchPath_.empty() &&
                       std::filesystem::is_directory(searchPath_.front() + "/" + top);
    const std::size_t folders = owned ? 1 : searchPath_.size();
    for (std::size_t i = 0; i < folders; ++i)
        if (isFile(searchPath_[i] + "/" + name)) return resolveIn(searchPath_[i], name, name, where);
    std::string searched;
    for (std::size_t i = 0; i < folders; ++i) searched += (searched.empty() ? "" : ", ") + displayPath(searchPath_[i]);
    throw ShaderError(where + "shader '" + name + "' not found (searched: " + searched + ")");
}

std::vector<std::string> ShaderLibrary::resolveAll(const std::string& name, const std::string& includedFrom) const {
    const std::string every = kStagesPrefix + "*/";
    if (name.rfind(every, 0) != 0) return {resolve(name, includedFrom)};
    checkIncludeName(name, includedFrom.empty() ? "" : includedFrom + ": ");
    // The stages from the build's list, not from listing the folder: a
    // grading worker may read the stages' shader files but not list their
    // folders (stage_job.cpp), and the list keeps the teaching order.
    static const char* const stages[] = {
#define VOXLAB_STAGE(stage) #stage,
#include "voxlab_stage_names.inc"
#undef VOXLAB_STAGE
    };
    const std::string file = name.substr(every.size());
    std::vector<std::string> found;
    for (const char* stage : stages)
        if (isFile(stagesRoot() + "/" + stage + "/" + file))
            found.push_back(resolve(kStagesPrefix + stage + "/" + file, includedFrom));
    return found;
}

PreprocessedShader ShaderLibrary::preprocess(const std::string& name, const ShaderConstants& given) const {
    ShaderConstants constants = globalConstants_;
    for (const auto& [key, value] : given) constants[key] = value;
    Preprocessor p{*this, constants, {}, {}, {}};
    p.addFile(resolve(name), true);
    return p.out;
}

ShaderProgram::ShaderProgram(const ShaderLibrary& library, const std::string& vertexName,
                             const std::string& fragmentName, const ShaderConstants& constants) {
    const PreprocessedShader vs = library.preprocess(vertexName, constants);
    const PreprocessedShader fs = library.preprocess(fragmentName, constants);
    files_ = vs.files;
    files_.insert(files_.end(), fs.files.begin(), fs.files.end());
    stubs_ = fs.stubs;
    const GLuint v = compileStage(GL_VERTEX_SHADER, vs);
    GLuint f = 0;
    try {
        const auto profile = constants.find("u_profile");
        if (profile != constants.end() && profile->second == 2)
            f = compileStage(GL_FRAGMENT_SHADER, withProfileRecord(fs));
        else if (library.compileOnce() && currentGlRenderer().find("llvmpipe") != std::string::npos)
            f = compileStage(GL_FRAGMENT_SHADER, compiledOnceOnLlvmpipe(fs));
        else
            f = compileStage(GL_FRAGMENT_SHADER, fs);
    } catch (...) {
        glDeleteShader(v);
        throw;
    }
    program_ = glCreateProgram();
    glAttachShader(program_, v);
    glAttachShader(program_, f);
    glLinkProgram(program_);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(program_, GL_LINK_STATUS, &ok);
    if (!ok) {
        const std::string log = infoLog(program_, glGetProgramiv, glGetProgramInfoLog);
        glDeleteProgram(program_);
        program_ = 0;
        throw ShaderError(fragmentName + ": link error: " + fs.mapLog(log));
    }
    parkSamplerUniforms(program_);
}

ShaderProgram::~ShaderProgram() {
    if (program_) glDeleteProgram(program_);
}

void ShaderProgram::use() const { glUseProgram(program_); }

int ShaderProgram::location(const char* name) const {
    auto it = locations_.find(name);
    if (it != locations_.end()) return it->second;
    const int loc = glGetUniformLocation(program_, name);
    locations_.emplace(name, loc);
    return loc;
}

void ShaderProgram::set(const char* name, int v) const { glUniform1i(location(name), v); }
void ShaderProgram::set(const char* name, float v) const { glUniform1f(location(name), v); }
void ShaderProgram::set(const char* name, glm::vec2 v) const { glUniform2f(location(name), v.x, v.y); }
void ShaderProgram::set(const char* name, glm::vec3 v) const { glUniform3f(location(name), v.x, v.y, v.z); }
void ShaderProgram::set(const char* name, glm::vec4 v) const {
    glUniform4f(location(name), v.x, v.y, v.z, v.w);
}
void ShaderProgram::set(const char* name, glm::ivec3 v) const { glUniform3i(location(name), v.x, v.y, v.z); }
void ShaderProgram::set(const char* name, const glm::mat4& m) const {
    glUniformMatrix4fv(location(name), 1, GL_FALSE, &m[0][0]);
}

void checkGlError(const char* where) {
    const GLenum err = glGetError();
    const std::string reported = strictGlChecks() ? strictGlDebugErrors() : "";
    if (err == GL_NO_ERROR && !reported.empty()) throw Error("OpenGL: " + reported + " (after " + where + ")");
    if (err == GL_NO_ERROR) return;
    const char* name = "unknown";
    switch (err) {
        case GL_INVALID_ENUM: name = "GL_INVALID_ENUM"; break;
        case GL_INVALID_VALUE: name = "GL_INVALID_VALUE"; break;
        case GL_INVALID_OPERATION: name = "GL_INVALID_OPERATION"; break;
        case GL_INVALID_FRAMEBUFFER_OPERATION: name = "GL_INVALID_FRAMEBUFFER_OPERATION"; break;
        case GL_OUT_OF_MEMORY: name = "GL_OUT_OF_MEMORY"; break;
    }
    while (glGetError() != GL_NO_ERROR) {}
    throw Error(std::string("OpenGL error ") + name + " after " + where + (reported.empty() ? "" : ": " + reported));
}

void checkGlDraw(const char* where) {
    // What a strict driver refuses first: Mesa may answer the same draw with
    // a bare GL_INVALID_OPERATION, which says less.
    const std::string problems = strictGlProblems();
    if (!problems.empty()) {
        while (glGetError() != GL_NO_ERROR) {}
        throw Error("OpenGL: " + problems + " (" + where + ")");
    }
    checkGlError(where);
}

}  // namespace voxlab
