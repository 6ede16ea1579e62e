// voxlab: the parts of GlContext shared by every backend.
#include "voxlab/gl_context.h"
#include "voxlab/shader.h"

#include <cstdlib>
#include <cstring>

#ifdef VOXLAB_SANITIZED
#include <dlfcn.h>
#include <link.h>
#endif

#include "voxlab/error.h"
#include "voxlab_gl.h"

namespace voxlab {

namespace {

// Sanitizer builds only (VOXLAB_SANITIZE=ON). Mesa unloads its DRI driver
// (swrast_dri.so) when an EGL display or GLX connection closes; the few
// hundred bytes the driver still holds then become unreachable and
// LeakSanitizer reports them against "<unknown module>", which no
// suppression can name. Marking every loaded DRI driver RTLD_NODELETE keeps
// it mapped until exit, and what it holds reachable from its globals.
void keepDriDriversLoaded() {
#ifdef VOXLAB_SANITIZED
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void*) {
            if (info->dlpi_name && std::strstr(info->dlpi_name, "_dri.so"))
                dlopen(info->dlpi_name, RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
            return 0;
        },
        nullptr);
#endif
}

}  // namespace

void GlContext::loadFunctions(const char* kind) {
    keepDriDriversLoaded();
    kind_ = kind;
    // voxlabLoadGL accepts any get-proc-address function; each backend
    // hands us its own through this trampoline.
    static thread_local const GlContext* current = nullptr;
    current = this;
    const int missing = voxlabLoadGL([](const char* name) -> VoxlabGLProc {
        return reinterpret_cast<VoxlabGLProc>(current->getProcAddress(name));
    });
    if (missing > 0)
        throw Error(std::string(kind) + ": OpenGL 3.3 core is not available (" +
                    std::to_string(missing) + " functions missing, first: " + voxlabGLMissing(0) + ")");
#ifdef __EMSCRIPTEN__
    return;  // WebGL 2 (OpenGL ES 3.0): what the browser build is written for
#endif
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < 3 || (major == 3 && minor < 3))
        throw Error(std::string(kind) + ": OpenGL " + std::to_string(major) + "." +
                    std::to_string(minor) + " found, 3.3 core or newer is needed");
    if (strictGlChecksWanted()) enableStrictGlChecks(*this);
}

namespace {

// A string of the current context (glGetString), or `missing` without one.
std::string glString(GLenum name, const char* missing) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string(missing);
}

}  // namespace

std::string currentGlRenderer() { return glString(GL_RENDERER, ""); }

std::string GlContext::description() const {
    return kind_ + ": " + glString(GL_RENDERER, "?") + ", OpenGL " + glString(GL_VERSION, "?");
}

#ifdef VOXLAB_HAVE_OSMESA
constexpr bool kHaveOsMesa = true;
#else
constexpr bool kHaveOsMesa = false;  // macOS, Windows, the browser: no OSMesa
#endif

HeadlessBackend parseHeadlessBackend(const std::string& name) {
    if (name.empty() || name == "auto") return HeadlessBackend::Auto;
    if (name == "osmesa") return HeadlessBackend::OSMesa;
    if (name == "egl") return HeadlessBackend::EGL;
    throw Error("unknown GL backend '" + name + "' (expected auto, osmesa or egl)");
}

std::unique_ptr<GlContext> createHeadlessContext(HeadlessBackend backend) {
    if (backend == HeadlessBackend::Auto) {
        const char* env = std::getenv("VOXLAB_GL");
        backend = parseHeadlessBackend(env ? env : "");
        if (backend == HeadlessBackend::Auto) backend = kHaveOsMesa ? HeadlessBackend::OSMesa : HeadlessBackend::EGL;
    }
    return backend == HeadlessBackend::EGL ? createEglContext() : createOsMesaContext();
}

#ifndef VOXLAB_HAVE_OSMESA
std::unique_ptr<GlContext> createOsMesaContext() {
    throw Error("OSMesa: this build of voxlab has no OSMesa (headless rendering on the CPU; Linux's "
                "libosmesa6-dev was not found at configure time): use --gl egl, or the viewer");
}
#endif

#ifndef VOXLAB_HAVE_EGL
std::unique_ptr<GlContext> createEglContext() {
    throw Error("EGL: this build of voxlab has no EGL support (libEGL was not found at configure time)");
}
#endif

}  // namespace voxlab
