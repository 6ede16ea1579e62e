// voxlab: headless OpenGL through EGL (GPU drivers, or Mesa's surfaceless
// platform). Optional: built only where libEGL is found. Renders into
// framebuffer objects, so no surface is created at all.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

#include "voxlab/error.h"
#include "voxlab/gl_context.h"

namespace voxlab {
namespace {

std::string eglErrorText(const char* what) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " (EGL error 0x%04x)", eglGetError());
    return std::string("EGL: ") + what + buf;
}

// Picks a display: the first EGL device (a GPU without X or Wayland) when the
// device extensions exist, else the default display.
EGLDisplay openDisplay() {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (queryDevices && getPlatformDisplay) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (queryDevices(8, devices, &count) && count > 0) {
            for (EGLint i = 0; i < count; ++i) {
                EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                EGLint major = 0, minor = 0;
                if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
            }
        }
    }
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    EGLint major = 0, minor = 0;
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor)) return EGL_NO_DISPLAY;
    return d;
}

class EglContext final : public GlContext {
public:
    EglContext() {
        display_ = openDisplay();
        if (display_ == EGL_NO_DISPLAY) throw Error(eglErrorText("no display could be initialised"));
        if (!eglBindAPI(EGL_OPENGL_API)) throw Error(eglErrorText("desktop OpenGL is not supported"));
        const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        eglChooseConfig(display_, configAttribs, &config, 1, &count);  // may be none: surfaceless
        const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        context_ = eglCreateContext(display_, count > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                                    contextAttribs);
        if (context_ == EGL_NO_CONTEXT) throw Error(eglErrorText("could not create a 3.3 core context"));
        makeCurrent();
        loadFunctions("EGL");
    }
    ~EglContext() override {
        if (context_ != EGL_NO_CONTEXT) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display_, context_);
        }
        if (display_ != EGL_NO_DISPLAY) eglTerminate(display_);
    }
    void makeCurrent() override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw Error(eglErrorText("eglMakeCurrent without a surface failed"));
    }
    GlProc getProcAddress(const char* name) const override {
        return reinterpret_cast<GlProc>(eglGetProcAddress(name));
    }

private:
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext() { return std::make_unique<EglContext>(); }

}  // namespace voxlab
