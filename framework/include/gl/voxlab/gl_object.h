#pragma once
// voxlab: OpenGL object names with an owner.
//
// A GlObject holds one name (a texture, framebuffer, renderbuffer, buffer,
// vertex array or query): made by make() or ensure() (glGen*), deleted when its
// owner goes or reset() is called (glDelete*), moved but never copied. It
// converts to the name, so it is passed to GL as the name itself
// (glBindTexture(GL_TEXTURE_3D, texture)). Objects are made and deleted on
// the thread whose GL context is current, as every GL call is; an owner
// outlives no context it made objects in. Nothing outside this file calls
// glGen* or glDelete* for these kinds (shader programs are owned by
// ShaderProgram).
#include <utility>

namespace voxlab {

namespace gl_object {
// Each kind's glGen* and glDelete* for one name (gl_object.cpp).
struct Texture { static void make(unsigned* n); static void drop(unsigned n); };
struct Framebuffer { static void make(unsigned* n); static void drop(unsigned n); };
struct Renderbuffer { static void make(unsigned* n); static void drop(unsigned n); };
struct Buffer { static void make(unsigned* n); static void drop(unsigned n); };
struct VertexArray { static void make(unsigned* n); static void drop(unsigned n); };
struct Query { static void make(unsigned* n); static void drop(unsigned n); };
}  // namespace gl_object

template <class Kind>
class GlObject {
public:
    GlObject() = default;  // no object yet: the name 0
    ~GlObject() { reset(); }
    GlObject(GlObject&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;

    // A new object, in place of the one held (which is deleted).
    static GlObject make() {
        GlObject object;
        Kind::make(&object.name_);
        return object;
    }
    // Makes an object unless one is held; returns its name.
    unsigned ensure() {
        if (!name_) Kind::make(&name_);
        return name_;
    }
    // Deletes the object held, if any.
    void reset() {
        if (name_) Kind::drop(name_);
        name_ = 0;
    }
    // Gives the name up without deleting it: for an object whose context
    // is already gone (deleting it then would call into no context).
    unsigned release() { return std::exchange(name_, 0); }
    unsigned name() const { return name_; }
    operator unsigned() const { return name_; }

private:
    unsigned name_ = 0;
};

using GlTexture = GlObject<gl_object::Texture>;
using GlFramebuffer = GlObject<gl_object::Framebuffer>;
using GlRenderbuffer = GlObject<gl_object::Renderbuffer>;
using GlBuffer = GlObject<gl_object::Buffer>;
using GlVertexArray = GlObject<gl_object::VertexArray>;
using GlQuery = GlObject<gl_object::Query>;

// A float RGBA colour target with a 24-bit depth buffer, its three objects
// owned (the render engine's image, layers and intermediate images).
struct FloatTarget {
    GlFramebuffer framebuffer;
    GlTexture color;
    GlRenderbuffer depth;
    // New objects of this size in place of the old ones. Throws
    // voxlab::Error when the framebuffer is not complete.
    void make(int width, int height) { makeTogether(this, 1, width, height); }
    bool made() const { return framebuffer.name() != 0; }
    // `count` targets made anew together, every new object (storage
    // included) before any old one goes (gl_object.cpp says why).
    static void makeTogether(FloatTarget* targets, int count, int width, int height);
};

}  // namespace voxlab
