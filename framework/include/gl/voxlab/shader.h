// voxlab: GLSL programs built from small guarded function libraries.
//
// Shader files are found through a search path, never relative to the
// working directory. The usual path is
//   [ implementation root (reference/ or a student's submission),
//     <project>/shaders ]
// so that `#include "mip/mip.glsl"` picks the implementation being run, and
// `#include "voxlab/ray.glsl"` picks the framework's library.
//
// The preprocessor here handles `#include "file"` only (the GL compiler does
// the rest). Each file is included at most once per program, and `#line`
// directives keep line numbers: a compile error is reported as
// "reference/mip/mip.glsl:14:9: error: ...", naming the file and line.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/error.h"

namespace voxlab {

// Thrown for compile and link failures; what() is the mapped compiler log,
// first line first ("path:line:col: error: ...").
class ShaderError : public Error {
public:
    using Error::Error;
};

struct PreprocessedShader {
    std::string text;
    std::vector<std::string> files;  // index = file id, encoded in #line numbers
    // The starter code's stubs in the text, "stage/function" (the file's
    // folder and the function whose body calls not_implemented()): the
    // stub's call is numbered, `not_implemented_at(K)` for stubs[K], so that
    // a render can say which stubs its pixels reached (voxlab/not_implemented.glsl).
    std::vector<std::string> stubs;

    // Rewrites "S:L(C): ..." (Mesa) and "S(L) : ..." (NVIDIA) into
    // "file:line:C: ...". Line numbers carry the file: L = id*100000 + line.
    std::string mapLog(const std::string& log) const;
};

// Integer uniforms baked into a program as constants: a declaration
// `uniform int NAME;` (or bool) whose NAME is listed becomes
// `const int NAME = VALUE;`. The GLSL reads the same either way, but the
// compiler folds branches on a constant away. That matters on CPU
// rasterizers (llvmpipe runs both sides of a uniform branch), so the render
// engine bakes the switches (interpolation, bool parameters) and keeps one
// program per combination.
using ShaderConstants = std::map<std::string, int>;

// Shaders are written once, in GLSL 330 core (their first line says so). The
// preprocessor gives each context the dialect it compiles:
//   - Core330: the text as written (OpenGL 3.3 core and newer, macOS's 4.1);
//   - Es300: GLSL ES 3.00, for WebGL 2 (the browser build). The version line
//     becomes `#version 300 es` followed by precision statements (highp for
//     float, int and every sampler type), nothing else changes.
// What a shader must therefore keep to, to be valid in both (docs/web.md;
// checked for every bundled shader by tests/test_glsl_es.cpp):
//   - no implicit conversions: 1.0 not 1 where a float is meant, float(i)
//     for an int, uint literals with their u;
//   - no features outside ES 3.00: no noperspective, no gl_ClipDistance,
//     no double, no texture functions with an explicit bias on a sampler3D's
//     integer variant; every fragment output with a layout(location = N)
//     when there is more than one.
enum class GlslDialect { Core330, Es300 };
GlslDialect nativeGlslDialect();  // Es300 in the browser build, else Core330
// The lines that replace an entry shader's first line, `#version 330 core`,
// in `dialect`; throws ShaderError naming `where` for any other first line.
std::string versionPreamble(const std::string& firstLine, GlslDialect dialect, const std::string& where);

class ShaderLibrary {
public:
    explicit ShaderLibrary(std::vector<std::string> searchPath);
    // The default path: [implementationRoot, <project>/reference,
    // <project>/shaders]. A stage the implementation root does not contain
    // (a submission of one assignment) comes from the reference solution;
    // a stage folder it does contain is searched alone, so an empty or
    // incomplete stage never borrows the reference's files.
    static ShaderLibrary forImplementation(const std::string& implementationRoot);

    const std::vector<std::string>& searchPath() const { return searchPath_; }
    // A shader made in memory (a renderer's generated entry shader, see
    // Renderer::generatedShaders): `name` resolves to it before the search
    // path, and compile errors name it "generated:NAME".
    void addGenerated(const std::string& name, const std::string& text);
    // Absolute path of `name`, first match on the search path; throws
    // ShaderError when absent, when `name` is absolute or has a ".." part,
    // or when the file found lies outside its folder through a link. A name
    // "stages/STAGE/FILE" is a stage's framework shader (its entry, probe or
    // precomputation pass) and is found under stagesRoot() alone: no
    // implementation can bring its own.
    std::string resolve(const std::string& name, const std::string& includedFrom = "") const;
    // What an #include of `name` reads: resolve(name), or for a name
    // "stages/*/FILE" every stage folder's FILE, in the stages' teaching
    // order (framework/stages/stages.cmake; none when no stage has one).
    // That is how a stage adds a segment to a framework shader without the
    // shader naming it: ray.glsl includes "stages/*/ray_segment.glsl".
    std::vector<std::string> resolveAll(const std::string& name, const std::string& includedFrom = "") const;
    PreprocessedShader preprocess(const std::string& name, const ShaderConstants& constants = {}) const;
    GlslDialect dialect() const { return dialect_; }
    void setDialect(GlslDialect dialect) { dialect_ = dialect; }
    // On llvmpipe, each fragment shader compiled once instead of twice, for
    // a few per cent of its speed (see shader.cpp): for a process that draws
    // each program a few times, as a grading worker does. Other drivers
    // compile the shader as written either way.
    void setCompileOnce(bool on) { compileOnce_ = on; }
    bool compileOnce() const { return compileOnce_; }
    // A constant baked into every program compiled from now on (as the
    // constants given to preprocess() are), such as u_exact_filtering
    // (voxlab/filtering.glsl); a program's own constants win.
    void setGlobalConstant(const std::string& name, int value) { globalConstants_[name] = value; }

    // The text of a generated shader, by the path resolve() gave it.
    const std::string* generatedText(const std::string& path) const;

private:
    std::vector<std::string> searchPath_;
    std::map<std::string, std::string> generated_;  // "generated:NAME" -> text
    GlslDialect dialect_ = nativeGlslDialect();
    bool compileOnce_ = false;
    ShaderConstants globalConstants_;
};

class ShaderProgram {
public:
    ShaderProgram(const ShaderLibrary& library, const std::string& vertexName,
                  const std::string& fragmentName, const ShaderConstants& constants = {});
    ~ShaderProgram();
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    void use() const;
    unsigned id() const { return program_; }
    // Every file that went into the program (for live reload).
    const std::vector<std::string>& sourceFiles() const { return files_; }
    // The stubs compiled into its fragment shader, by number (PreprocessedShader::stubs).
    const std::vector<std::string>& stubs() const { return stubs_; }

    // Uniform setters; silently ignore uniforms the compiler removed.
    void set(const char* name, int v) const;
    void set(const char* name, float v) const;
    void set(const char* name, glm::vec2 v) const;
    void set(const char* name, glm::vec3 v) const;
    void set(const char* name, glm::vec4 v) const;
    void set(const char* name, glm::ivec3 v) const;
    void set(const char* name, const glm::mat4& m) const;
    int location(const char* name) const;

private:
    unsigned program_ = 0;
    std::vector<std::string> files_;
    std::vector<std::string> stubs_;
    mutable std::map<std::string, int> locations_;
};

// Throws voxlab::Error("OpenGL error GL_INVALID_OPERATION after <where>") if
// the GL error flag is set, or, with strict checks on, the driver reported
// an error through KHR_debug.
void checkGlError(const char* where);

// checkGlError after a draw: with strict checks on, also what a GPU's driver
// refuses to draw and Mesa draws (two sampler types on one texture unit).
void checkGlDraw(const char* where);

// Points every active sampler uniform of `program` at a texture unit of its
// own type's (16 and up, past the units voxlab binds), so that a sampler
// the engine never sets (one that this driver keeps active and another
// optimises away) cannot share unit 0 with a sampler of another type: a
// GPU's driver refuses such a draw. ShaderProgram does it after linking.
void parkSamplerUniforms(unsigned program);

// Strict checks (gl_strict.cpp): KHR_debug errors and the GL rules Mesa
// does not enforce, for the current thread's context. Wanted where
// $VOXLAB_GL_DEBUG is set (the tests set it); GlContext turns them on.
class GlContext;
void enableStrictGlChecks(const GlContext& context);
bool strictGlChecksWanted();
bool strictGlChecks();
// What the checks found since the last call ("" when nothing or off).
std::string strictGlProblems();
std::string strictGlDebugErrors();

}  // namespace voxlab
