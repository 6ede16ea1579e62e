// voxlab: headless OpenGL through OSMesa (Mesa's off-screen interface).
//
// This file includes <GL/osmesa.h>, which pulls in the system <GL/gl.h>;
// it therefore must not include voxlab_gl.h. It only creates the context and
// hands out OSMesaGetProcAddress; GlContext::loadFunctions does the rest.
#include <GL/osmesa.h>

#include <vector>

#include "voxlab/error.h"
#include "voxlab/gl_context.h"

namespace voxlab {
namespace {

class OsMesaContext final : public GlContext {
public:
    OsMesaContext() {
        // Ask for the newest core profile first (llvmpipe gives 4.5), then 3.3.
        const int versions[][2] = {{4, 5}, {4, 1}, {3, 3}};
        for (const auto& v : versions) {
            const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                                   OSMESA_STENCIL_BITS, 0, OSMESA_ACCUM_BITS, 0,
                                   OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                                   OSMESA_CONTEXT_MAJOR_VERSION, v[0],
                                   OSMESA_CONTEXT_MINOR_VERSION, v[1], 0};
            ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
            if (ctx_) break;
        }
        if (!ctx_) throw Error("OSMesa: could not create an OpenGL 3.3 core-profile context");
        makeCurrent();
        loadFunctions("OSMesa");
    }
    ~OsMesaContext() override {
        if (ctx_) OSMesaDestroyContext(ctx_);
    }
    void makeCurrent() override {
        // Renderers draw into framebuffer objects; the context's own buffer
        // only has to exist.
        if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1))
            throw Error("OSMesa: OSMesaMakeCurrent failed");
    }
    GlProc getProcAddress(const char* name) const override {
        return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
    }

private:
    OSMesaContext ctx_ = nullptr;
    std::vector<unsigned char> buffer_ = std::vector<unsigned char>(4);
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext() { return std::make_unique<OsMesaContext>(); }

}  // namespace voxlab
