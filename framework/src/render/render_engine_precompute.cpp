// voxlab: textures a renderer computes on the GPU before it draws (see
// Precomputation in renderer.h): the pre-integration table, the light
// volume.
//
// A texture is made by running its fragment shader over a full-screen
// triangle into the texture (a 3D texture layer by layer, each layer
// attached to the framebuffer in turn), with the pass's uniforms. It is
// kept, and made again only when what it depends on changes: the
// renderer's key, the volume, the transfer function, the baked switches or
// the shaders (a live reload). While the camera moves over a still scene
// nothing is recomputed, unless the key says so (a light that turns with
// the camera).
#include <string>

#include "voxlab/error.h"
#include "voxlab/render_engine.h"
#include "voxlab_gl.h"

namespace voxlab {
namespace {

constexpr int kFirstPrecomputedUnit = 6;  // after the bricks (5)
constexpr int kMaxPrecomputations = 2;

std::string fullKey(const Precomputation& what, const ShaderConstants& constants, unsigned long volume,
                    unsigned long tf, unsigned long shaders) {
    std::string key = what.fragmentShader + "|" + what.key + "|v" + std::to_string(volume) + "|t" +
                      std::to_string(tf) + "|s" + std::to_string(shaders) + "|" + std::to_string(what.size.x) + "x" +
                      std::to_string(what.size.y) + "x" + std::to_string(what.size.z);
    for (const auto& [name, value] : constants) key += "|" + name + "=" + std::to_string(value);
    return key;
}

void allocate(unsigned texture, glm::ivec3 size, int channels) {
    const GLenum internal = channels == 1 ? GL_R32F : GL_RGBA32F, format = channels == 1 ? GL_RED : GL_RGBA;
    const GLenum target = size.z > 1 ? GL_TEXTURE_3D : GL_TEXTURE_2D;
    glBindTexture(target, texture);
    if (size.z > 1)
        glTexImage3D(target, 0, GLint(internal), size.x, size.y, size.z, 0, format, GL_FLOAT, nullptr);
    else
        glTexImage2D(target, 0, GLint(internal), size.x, size.y, 0, format, GL_FLOAT, nullptr);
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(target, wrap, GL_CLAMP_TO_EDGE);
}

}  // namespace

void RenderEngine::runPrecomputation(const Precomputation& what, int index, const Scene& scene, const Pass& pass,
                                     const PassInputs& inputs, const ShaderConstants& constants) {
    if (index >= kMaxPrecomputations)
        throw Error("renderer '" + pass.renderer->id() + "' asks for more than " +
                    std::to_string(kMaxPrecomputations) + " precomputed textures");
    if (what.size.x < 1 || what.size.y < 1 || what.size.z < 1 || (what.channels != 1 && what.channels != 4))
        throw Error("renderer '" + pass.renderer->id() + "': precomputed texture " + what.sampler +
                    " has an invalid size or channel count");
    PrecomputedTexture& made = precomputed_[{pass.slot, index}];
    const std::string key =
        fullKey(what, constants, volumeGeneration_, tf_[pass.slot].generation, shaderGeneration_);
    if (made.texture && made.key == key) return;

    const ShaderProgram& prog = program("voxlab/fullscreen.vert", what.fragmentShader, constants);
    precomputeFbo_.ensure();
    if (!made.texture || made.size != what.size || made.channels != what.channels) {
        // A new texture name each time: a name once bound as a 2D texture
        // cannot become a 3D one (another renderer's texture in this slot).
        made.texture = GlTexture::make();
        allocate(made.texture, what.size, what.channels);
        made.size = what.size, made.channels = what.channels;
    }
    GLint framebuffer = 0, viewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    glGetIntegerv(GL_VIEWPORT, viewport);

    prog.use();
    setPassUniforms(prog, scene, pass, inputs);
    prog.set("u_precompute_size", what.size);
    glBindFramebuffer(GL_FRAMEBUFFER, precomputeFbo_);
    glViewport(0, 0, what.size.x, what.size.y);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(vao_);
    for (int layer = 0; layer < what.size.z; ++layer) {
        if (what.size.z > 1)
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, made.texture, 0, layer);
        else
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, made.texture, 0);
        if (layer == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error("OpenGL: cannot render into the precomputed texture " + what.sampler);
        prog.set("u_precompute_layer", layer);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    checkGlDraw(("computing " + what.sampler).c_str());
    made.key = key;
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

void RenderEngine::bindPrecomputations(const ShaderProgram& prog, const std::vector<Precomputation>& what,
                                       int slot) {
    for (std::size_t i = 0; i < what.size(); ++i) {
        const PrecomputedTexture& made = precomputed_.at({slot, int(i)});
        glActiveTexture(GL_TEXTURE0 + kFirstPrecomputedUnit + GLenum(i));
        glBindTexture(made.size.z > 1 ? GL_TEXTURE_3D : GL_TEXTURE_2D, made.texture);
        prog.set(what[i].sampler.c_str(), kFirstPrecomputedUnit + int(i));
    }
}

}  // namespace voxlab
