// voxlab: strict GL checks (see shader.h, enableStrictGlChecks).
//
// Mesa accepts some things the GL specification forbids and a GPU's driver
// refuses at draw time; a verdict that holds on any conforming GL must not
// depend on them. With the checks on:
//   - KHR_debug (GL 4.3, or the extension) reports every error the driver
//     raises, with its own message, synchronously;
//   - before a draw is accepted, no texture unit may be pointed at by two
//     active samplers of different types (GL 3.3 core, 2.11.7: "It is not
//     allowed to have variables of different sampler types pointing to the
//     same texture image unit within a program object"; NVIDIA's driver
//     answers GL_INVALID_OPERATION, Mesa draws).
// The checks run in the tests (VOXLAB_GL_DEBUG=1 in their environment) and
// wherever VOXLAB_GL_DEBUG is set; they cost a few GL queries a draw.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "voxlab/error.h"
#include "voxlab/gl_context.h"
#include "voxlab/shader.h"
#include "voxlab_gl.h"

namespace voxlab {

namespace {

// KHR_debug's entry points and values, which the 3.3 loader leaves out.
using DebugProc = void (*)(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                           const GLchar* message, const void* user);
using DebugMessageCallback = void (*)(DebugProc callback, const void* user);
constexpr GLenum kDebugOutput = 0x92E0, kDebugOutputSynchronous = 0x8242, kDebugTypeError = 0x824C,
                 kDebugSourceShaderCompiler = 0x8248;

// Plain arrays, not a std::vector: a driver may report while a context is
// destroyed at exit, after a thread_local vector would be gone.
constexpr int kKept = 8, kMessageBytes = 300;
thread_local bool strict = false;
thread_local int debugErrorCount = 0;
thread_local char debugErrors[kKept][kMessageBytes];

// Errors only; a shader's compile errors are ShaderError's to report (a
// student's mistake, not the framework's).
void collect(GLenum source, GLenum type, GLuint, GLenum, GLsizei length, const GLchar* message, const void*) {
    if (type != kDebugTypeError || source == kDebugSourceShaderCompiler || debugErrorCount >= kKept) return;
    const std::size_t n = std::min<std::size_t>(length > 0 ? std::size_t(length) : std::strlen(message), kMessageBytes - 1);
    std::memcpy(debugErrors[debugErrorCount], message, n);
    debugErrors[debugErrorCount++][n] = '\0';
}

const char* samplerTypeName(GLenum type) {
    switch (type) {
        case GL_SAMPLER_1D: return "sampler1D";
        case GL_SAMPLER_2D: return "sampler2D";
        case GL_SAMPLER_3D: return "sampler3D";
        case GL_SAMPLER_CUBE: return "samplerCube";
        case GL_SAMPLER_2D_ARRAY: return "sampler2DArray";
        case GL_SAMPLER_2D_SHADOW: return "sampler2DShadow";
        case GL_SAMPLER_BUFFER: return "samplerBuffer";
        case GL_INT_SAMPLER_2D: return "isampler2D";
        case GL_INT_SAMPLER_3D: return "isampler3D";
        case GL_UNSIGNED_INT_SAMPLER_2D: return "usampler2D";
        case GL_UNSIGNED_INT_SAMPLER_3D: return "usampler3D";
        case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY: return "usampler2DArray";
        case GL_INT_SAMPLER_2D_ARRAY: return "isampler2DArray";
        default: return nullptr;  // not a sampler (or one voxlab does not use)
    }
}

// "" or what makes a strict driver refuse to draw with `program`.
std::string samplerConflicts(GLuint program) {
    GLint count = 0;
    glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &count);
    std::map<GLint, std::pair<GLenum, std::string>> units;  // unit -> the first sampler on it
    for (GLint i = 0; i < count; ++i) {
        char name[256];
        GLsizei length = 0;
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(program, GLuint(i), sizeof name, &length, &size, &type, name);
        const char* typeName = samplerTypeName(type);
        if (!typeName) continue;
        std::string base(name, std::size_t(length));
        if (base.size() > 3 && base.compare(base.size() - 3, 3, "[0]") == 0) base.resize(base.size() - 3);
        for (GLint e = 0; e < size; ++e) {
            const std::string element = size > 1 ? base + "[" + std::to_string(e) + "]" : base;
            GLint unit = 0;
            glGetUniformiv(program, glGetUniformLocation(program, element.c_str()), &unit);
            const auto [at, inserted] = units.emplace(unit, std::make_pair(type, element));
            if (!inserted && at->second.first != type)
                return "texture unit " + std::to_string(unit) + " is used by " +
                       samplerTypeName(at->second.first) + " " + at->second.second + " and by " + typeName + " " +
                       element + " (a GPU's driver refuses such a draw with GL_INVALID_OPERATION)";
        }
    }
    return "";
}

// The order in which parkSamplerUniforms gives sampler types their units.
int samplerTypeIndex(GLenum type) {
    static const GLenum order[] = {GL_SAMPLER_2D, GL_SAMPLER_3D, GL_SAMPLER_2D_ARRAY, GL_UNSIGNED_INT_SAMPLER_3D,
                                   GL_INT_SAMPLER_3D, GL_UNSIGNED_INT_SAMPLER_2D, GL_INT_SAMPLER_2D,
                                   GL_SAMPLER_1D, GL_SAMPLER_CUBE, GL_SAMPLER_2D_SHADOW, GL_SAMPLER_BUFFER,
                                   GL_UNSIGNED_INT_SAMPLER_2D_ARRAY, GL_INT_SAMPLER_2D_ARRAY};
    for (int i = 0; i < int(sizeof order / sizeof order[0]); ++i)
        if (order[i] == type) return i;
    return -1;
}

}  // namespace

void parkSamplerUniforms(unsigned program) {
    constexpr int kFirstParkingUnit = 16;
    GLint units = 0, count = 0, previous = 0;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
    glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &count);
    glGetIntegerv(GL_CURRENT_PROGRAM, &previous);
    glUseProgram(program);
    for (GLint i = 0; i < count; ++i) {
        char name[256];
        GLsizei length = 0;
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(program, GLuint(i), sizeof name, &length, &size, &type, name);
        const int index = samplerTypeIndex(type);
        if (index < 0 || kFirstParkingUnit + index >= units) continue;  // too few units: left as it is
        std::string base(name, std::size_t(length));
        if (base.size() > 3 && base.compare(base.size() - 3, 3, "[0]") == 0) base.resize(base.size() - 3);
        for (GLint e = 0; e < size; ++e) {
            const std::string element = size > 1 ? base + "[" + std::to_string(e) + "]" : base;
            glUniform1i(glGetUniformLocation(program, element.c_str()), kFirstParkingUnit + index);
        }
    }
    // The program current before may have been deleted while current (a
    // destroyed engine's last): it was gone as soon as this one was used, and
    // using its name again is GL_INVALID_VALUE at the next draw's check.
    glUseProgram(glIsProgram(GLuint(previous)) ? GLuint(previous) : 0);
}

void enableStrictGlChecks(const GlContext& context) {
    strict = true;
    debugErrorCount = 0;
    const auto callback = reinterpret_cast<DebugMessageCallback>(context.getProcAddress("glDebugMessageCallback"));
    if (!callback) return;  // no KHR_debug: the sampler check still runs
    glEnable(kDebugOutput);
    glEnable(kDebugOutputSynchronous);
    callback(&collect, nullptr);
    while (glGetError() != GL_NO_ERROR) {}  // a driver without the enums says so once
}

bool strictGlChecksWanted() {
    const char* v = std::getenv("VOXLAB_GL_DEBUG");
    return v && *v && std::string(v) != "0";
}

bool strictGlChecks() { return strict; }

std::string strictGlDebugErrors() {
    std::string problems;
    for (int i = 0; i < debugErrorCount; ++i) problems += (problems.empty() ? "" : "; ") + std::string(debugErrors[i]);
    debugErrorCount = 0;
    return problems;
}

std::string strictGlProblems() {
    if (!strict) return "";
    std::string problems = strictGlDebugErrors();
    GLint program = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    if (program > 0) {
        const std::string samplers = samplerConflicts(GLuint(program));
        if (!samplers.empty()) problems += (problems.empty() ? "" : "; ") + samplers;
    }
    return problems;
}

}  // namespace voxlab
