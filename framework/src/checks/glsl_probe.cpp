// voxlab (internal): the GLSL probe harness (see glsl_probe.h).
#include "voxlab/glsl_probe.h"

#include <algorithm>
#include <filesystem>
#include <string>

#include "voxlab/error.h"
#include "voxlab/scene.h"
#include "voxlab_gl.h"

namespace voxlab::probe {
namespace {

// Cases are laid out in rows of this many pixels.
constexpr int kRowLength = 64;
constexpr int kVolumeUnit = 0;
constexpr int kFirstInputUnit = 1;
constexpr int kTransferFunctionUnit = kFirstInputUnit + kProbeInputs;
constexpr int kTargets = 3;  // probe_result0, probe_result1, probe_status

// Restores what the probe changes, so that a render engine sharing the
// context finds its state as it left it.
class GlStateGuard {
public:
    GlStateGuard() {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer_);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer_);
        glGetIntegerv(GL_VIEWPORT, viewport_);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertexArray_);
        glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
    }
    ~GlStateGuard() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(drawFramebuffer_));
        glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(readFramebuffer_));
        glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
        glUseProgram(GLuint(program_));
        glBindVertexArray(GLuint(vertexArray_));
        glActiveTexture(GLenum(activeTexture_));
    }
    GlStateGuard(const GlStateGuard&) = delete;
    GlStateGuard& operator=(const GlStateGuard&) = delete;

private:
    GLint drawFramebuffer_ = 0, readFramebuffer_ = 0, viewport_[4] = {0, 0, 0, 0};
    GLint program_ = 0, vertexArray_ = 0, activeTexture_ = GL_TEXTURE0;
};

// The GL objects of one run(), deleted on every path out of it.
struct GlObjects {
    std::vector<GlTexture> textures;
    std::vector<GlFramebuffer> framebuffers;
    std::vector<GlVertexArray> vertexArrays;
};

GLuint floatTexture(GlObjects& objects, int width, int height, const float* texels) {
    objects.textures.push_back(GlTexture::make());
    const GLuint texture = objects.textures.back();
    glBindTexture(GL_TEXTURE_2D, texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return texture;
}

// The library for a probe. The GL functions are loaded when a context is
// created; calling them before would crash. The probe itself must be the
// framework's: a stage's probe is named "stages/STAGE/FILE", which only the
// framework's stage folders answer (ShaderLibrary::resolve).
ShaderLibrary probeLibrary(const std::string& implementationRoot, const std::string& fragmentName) {
    if (!glCreateProgram) throw Error("function checks: no OpenGL context (create one first)");
    ShaderLibrary library = ShaderLibrary::forImplementation(implementationRoot);
    // Filtering written out in float (voxlab/filtering.glsl): the same cases
    // give the same answers on every OpenGL.
    library.setGlobalConstant("u_exact_filtering", 1);
    if (fragmentName.rfind("stages/", 0) != 0)
        throw Error("function checks: probe shader '" + fragmentName + "' is not a stage's (stages/STAGE/FILE)");
    return library;
}

}  // namespace

GlslProbe::GlslProbe(const std::string& implementationRoot, const std::string& fragmentName,
                     const ShaderConstants& constants)
    : program_(probeLibrary(implementationRoot, fragmentName), "voxlab/fullscreen.vert", fragmentName, constants) {}

GlslProbe::~GlslProbe() = default;

void GlslProbe::setTransferFunction(const std::vector<glm::vec4>& entries, glm::vec2 range) {
    if (entries.size() < 2 || entries.size() > 4096) throw Error("probe transfer function: 2 to 4096 entries");
    GLint activeTexture = GL_TEXTURE0, program = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    tfTexture_.ensure();
    glActiveTexture(GL_TEXTURE0 + kTransferFunctionUnit);
    glBindTexture(GL_TEXTURE_2D, tfTexture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, GLsizei(entries.size()), 1, 0, GL_RGBA, GL_FLOAT, &entries[0].x);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glActiveTexture(GLenum(activeTexture));
    program_.use();
    program_.set("u_tf", kTransferFunctionUnit);
    program_.set("u_tf_range", range);
    program_.set("u_tf_size", int(entries.size()));
    program_.set("u_has_tf", 1);
    glUseProgram(GLuint(program));
    checkGlError("uploading a probe transfer function");
}

void GlslProbe::setVolume(const ProbeVolume& volume) {
    const glm::ivec3 d = volume.dims;
    if (std::size_t(d.x) * d.y * d.z != volume.values.size())
        throw Error("probe volume: " + std::to_string(volume.values.size()) + " values for " +
                    std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z) + " voxels");
    GLint activeTexture = GL_TEXTURE0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture);
    volumeTexture_.ensure();
    glActiveTexture(GL_TEXTURE0 + kVolumeUnit);
    glBindTexture(GL_TEXTURE_3D, volumeTexture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, d.x, d.y, d.z, 0, GL_RED, GL_FLOAT, volume.values.data());
    const GLint filter = volume.linearFilter ? GL_LINEAR : GL_NEAREST;
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, filter);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
    glActiveTexture(GLenum(activeTexture));

    GLint program = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    program_.use();
    const glm::vec3 spacing = volume.extent / glm::vec3(d);
    const auto [lo, hi] = std::minmax_element(volume.values.begin(), volume.values.end());
    program_.set("u_volume", kVolumeUnit);
    program_.set("u_volume_dims", d);
    program_.set("u_volume_extent", volume.extent);
    program_.set("u_value_scale", volume.valueScale);
    program_.set("u_value_offset", volume.valueOffset);
    program_.set("u_min_spacing", std::min({spacing.x, spacing.y, spacing.z}));
    program_.set("u_value_range", glm::vec2(*lo, *hi) * volume.valueScale + volume.valueOffset);
    glUseProgram(GLuint(program));
    checkGlError("uploading a probe volume");
}

ProbeResults GlslProbe::run(int cases, const std::vector<std::vector<glm::vec4>>& inputs,
                            const std::function<void(const ShaderProgram&, int)>& perCase) {
    if (cases <= 0) return {};
    if (int(inputs.size()) > kProbeInputs) throw Error("probe: more than " + std::to_string(kProbeInputs) + " inputs");
    const int width = std::min(cases, kRowLength), height = (cases + kRowLength - 1) / kRowLength;
    const std::size_t pixels = std::size_t(width) * height;

    GlStateGuard state;
    GlObjects objects;
    program_.use();
    if (volumeTexture_) {
        glActiveTexture(GL_TEXTURE0 + kVolumeUnit);
        glBindTexture(GL_TEXTURE_3D, volumeTexture_);
    }
    if (tfTexture_) {
        glActiveTexture(GL_TEXTURE0 + kTransferFunctionUnit);
        glBindTexture(GL_TEXTURE_2D, tfTexture_);
    }
    // The targets first: creating a texture binds it to the active unit,
    // which must not be one the probe reads.
    GLuint targets[kTargets] = {0, 0, 0};
    GLenum attachments[kTargets];
    glActiveTexture(GL_TEXTURE0 + kFirstInputUnit);
    for (int t = 0; t < kTargets; ++t) {
        targets[t] = floatTexture(objects, width, height, nullptr);
        attachments[t] = GL_COLOR_ATTACHMENT0 + GLenum(t);
    }
    for (std::size_t k = 0; k < inputs.size(); ++k) {
        if (int(inputs[k].size()) != cases) throw Error("probe: input " + std::to_string(k) + " has the wrong size");
        std::vector<glm::vec4> texels(inputs[k]);
        texels.resize(pixels, glm::vec4(0.0f));
        glActiveTexture(GL_TEXTURE0 + kFirstInputUnit + GLenum(k));
        floatTexture(objects, width, height, &texels[0].x);
        program_.set(("u_probe_input[" + std::to_string(k) + "]").c_str(), kFirstInputUnit + int(k));
    }

    objects.framebuffers.push_back(GlFramebuffer::make());
    const GLuint framebuffer = objects.framebuffers.back();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    for (int t = 0; t < kTargets; ++t)
        glFramebufferTexture2D(GL_FRAMEBUFFER, attachments[t], GL_TEXTURE_2D, targets[t], 0);
    glDrawBuffers(kTargets, attachments);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("OpenGL: the probe framebuffer is not complete");
    objects.vertexArrays.push_back(GlVertexArray::make());
    glBindVertexArray(objects.vertexArrays.back());
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);

    if (perCase) {
        // One case per draw, each into its own pixel (gl_FragCoord still
        // names that pixel, so the probe reads that case's inputs).
        for (int i = 0; i < cases; ++i) {
            perCase(program_, i);
            glViewport(i % width, i / width, 1, 1);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
    } else {
        glViewport(0, 0, width, height);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    checkGlDraw("drawing a function probe");

    std::vector<glm::vec4> read[kTargets];
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    for (int t = 0; t < kTargets; ++t) {
        read[t].resize(pixels);
        glReadBuffer(attachments[t]);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, &read[t][0].x);
    }
    checkGlError("reading back a function probe");

    ProbeResults results;
    results.first.assign(read[0].begin(), read[0].begin() + cases);
    results.second.assign(read[1].begin(), read[1].begin() + cases);
    for (int i = 0; i < cases; ++i) results.notImplemented = results.notImplemented || read[2][i].x != 0.0f;
    return results;
}

}  // namespace voxlab::probe
