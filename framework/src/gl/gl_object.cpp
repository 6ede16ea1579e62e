// voxlab: OpenGL object names with an owner (voxlab/gl_object.h).
#include "voxlab/gl_object.h"

#include <string>
#include <vector>

#include "voxlab/error.h"
#include "voxlab_gl.h"

namespace voxlab {
namespace gl_object {

void Texture::make(unsigned* n) { glGenTextures(1, n); }
void Texture::drop(unsigned n) { glDeleteTextures(1, &n); }
void Framebuffer::make(unsigned* n) { glGenFramebuffers(1, n); }
void Framebuffer::drop(unsigned n) { glDeleteFramebuffers(1, &n); }
void Renderbuffer::make(unsigned* n) { glGenRenderbuffers(1, n); }
void Renderbuffer::drop(unsigned n) { glDeleteRenderbuffers(1, &n); }
void Buffer::make(unsigned* n) { glGenBuffers(1, n); }
void Buffer::drop(unsigned n) { glDeleteBuffers(1, &n); }
void VertexArray::make(unsigned* n) { glGenVertexArrays(1, n); }
void VertexArray::drop(unsigned n) { glDeleteVertexArrays(1, &n); }
void Query::make(unsigned* n) { glGenQueries(1, n); }
void Query::drop(unsigned n) { glDeleteQueries(1, &n); }

}  // namespace gl_object

namespace {

// A new float target of this size, complete.
FloatTarget newTarget(int width, int height) {
    FloatTarget next;
    next.framebuffer = GlFramebuffer::make();
    next.color = GlTexture::make();
    next.depth = GlRenderbuffer::make();
    // A float target: the image is read back unrounded, and the one rounding
    // to 8 bits happens on the CPU by the README's rule.
    glBindTexture(GL_TEXTURE_2D, next.color);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindRenderbuffer(GL_RENDERBUFFER, next.depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, next.framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, next.color, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, next.depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("OpenGL: the float framebuffer (" + std::to_string(width) + "x" + std::to_string(height) +
                    ") is not complete");
    return next;
}

}  // namespace

// Every new object is made, storage included, before any old one goes:
// Mesa's softpipe caches a sampled texture's tiles by the address of its
// storage, and storage allocated where a just-deleted texture's was is taken
// for that texture. Shear-warp's two intermediate images, remade one at a
// time after a scene of another size in one process, showed the other's
// stale tiles: 13 % and 43 % of two grading scenes' pixels garbage.
void FloatTarget::makeTogether(FloatTarget* targets, int count, int width, int height) {
    std::vector<FloatTarget> next;
    next.reserve(std::size_t(count));
    for (int i = 0; i < count; ++i) next.push_back(newTarget(width, height));
    for (int i = 0; i < count; ++i) targets[i] = std::move(next[std::size_t(i)]);
}

}  // namespace voxlab
