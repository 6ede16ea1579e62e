// voxlab: the render engine's side of DrawContext (engine_draw_context.h).
#include "engine_draw_context.h"

#include <algorithm>

#include "voxlab/error.h"
#include "voxlab_gl.h"

namespace voxlab {

EngineDrawContext::EngineDrawContext(RenderEngine& engine, const Scene& scene, const Camera& camera,
                                     const ShaderProgram& program, const RenderEngine::Pass& pass,
                                     const RenderEngine::PassInputs& inputs, const ShaderConstants& constants)
    : engine_(engine), scene_(scene), camera_(camera), program_(&program), pass_(pass), inputs_(inputs),
      constants_(constants) {
    if (!engine_.geometryVao_) {
        engine_.geometryVao_ = GlVertexArray::make();
        engine_.geometryVbo_ = GlBuffer::make();
        engine_.geometryNormalVbo_ = GlBuffer::make();
        glBindVertexArray(engine_.geometryVao_);
        glBindBuffer(GL_ARRAY_BUFFER, engine_.geometryVbo_);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
        glBindBuffer(GL_ARRAY_BUFFER, engine_.geometryNormalVbo_);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    }
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &outputFramebuffer_);
    glGetIntegerv(GL_VIEWPORT, outputViewport_);
}

const Volume& EngineDrawContext::volume() const { return *engine_.volume_; }

const TransferFunction& EngineDrawContext::transferFunction() const {
    if (!inputs_.tf) throw Error("renderer '" + scene_.renderer + "' asked for a transfer function it did not declare");
    return *inputs_.tf;
}

void EngineDrawContext::drawArrays(unsigned mode, const std::vector<glm::vec3>& vertices,
                                   const std::vector<glm::vec3>* faceNormals) {
    if (vertices.empty()) return;
    glBindVertexArray(engine_.geometryVao_);
    glBindBuffer(GL_ARRAY_BUFFER, engine_.geometryVbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(glm::vec3)), vertices.data(), GL_STREAM_DRAW);
    if (faceNormals) {
        glBindBuffer(GL_ARRAY_BUFFER, engine_.geometryNormalVbo_);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(faceNormals->size() * sizeof(glm::vec3)), faceNormals->data(),
                     GL_STREAM_DRAW);
        glEnableVertexAttribArray(1);
    } else {
        glDisableVertexAttribArray(1);
        glVertexAttrib3f(1, 0.0f, 0.0f, 0.0f);  // no normal: the shader falls back
    }
    glDrawArrays(mode, 0, GLsizei(vertices.size()));
    if (strictGlChecks()) checkGlDraw(("drawing geometry for renderer '" + scene_.renderer + "'").c_str());
}

void EngineDrawContext::drawTriangles(const std::vector<glm::vec3>& vertices) { drawArrays(GL_TRIANGLES, vertices); }

void EngineDrawContext::drawFacets(const std::vector<glm::vec3>& vertices) {
    std::vector<glm::vec3> normals(vertices.size());
    for (std::size_t t = 0; t + 2 < vertices.size(); t += 3) {
        const glm::vec3 n = glm::cross(vertices[t + 1] - vertices[t], vertices[t + 2] - vertices[t]);
        const float length = glm::length(n);
        normals[t] = normals[t + 1] = normals[t + 2] = length > 0.0f ? n / length : glm::vec3(0.0f);
    }
    drawArrays(GL_TRIANGLES, vertices, &normals);
}

void EngineDrawContext::drawLines(const std::vector<glm::vec3>& vertices) {
    // Wide lines: not in a forward-compatible core context (GL 3.3 core
    // E.2.2), and only as wide as the implementation's range.
    GLint flags = 0;
#ifdef GL_CONTEXT_FLAG_FORWARD_COMPATIBLE_BIT  // (not in WebGL 2, whose range says what it draws)
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    const bool forwardCompatible = (flags & GL_CONTEXT_FLAG_FORWARD_COMPATIBLE_BIT) != 0;
#else
    const bool forwardCompatible = false;
#endif
    GLfloat range[2] = {1.0f, 1.0f};
    glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
    const bool wide = engine_.lineWidth_ > 1.0f && !forwardCompatible && range[1] > 1.0f;
    if (wide) glLineWidth(std::min(engine_.lineWidth_, range[1]));
    drawArrays(GL_LINES, vertices);
    if (wide) glLineWidth(1.0f);
}

void EngineDrawContext::drawInstancedSquares(const std::vector<glm::vec4>& instances) {
    if (instances.empty()) return;
    if (!engine_.pointVao_) {  // its own layout: 4 floats per instance
        engine_.pointVao_ = GlVertexArray::make();
        engine_.pointVbo_ = GlBuffer::make();
        glBindVertexArray(engine_.pointVao_);
        glBindBuffer(GL_ARRAY_BUFFER, engine_.pointVbo_);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(glm::vec4), nullptr);
        glVertexAttribDivisor(0, 1);
    }
    glBindVertexArray(engine_.pointVao_);
    glBindBuffer(GL_ARRAY_BUFFER, engine_.pointVbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(instances.size() * sizeof(glm::vec4)), instances.data(), GL_STREAM_DRAW);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 6, GLsizei(instances.size()));
    if (strictGlChecks()) checkGlDraw(("drawing instances for renderer '" + scene_.renderer + "'").c_str());
}

void EngineDrawContext::enableDepthTest() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
}

void EngineDrawContext::bindSliceStack(int axis, int unit) {
    const unsigned texture = engine_.sliceStack(axis);
    glActiveTexture(GL_TEXTURE0 + GLenum(unit));
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
}

const ShaderProgram& EngineDrawContext::useFullScreenProgram(const std::string& fragmentShader) {
    const ShaderProgram& prog = engine_.program("voxlab/fullscreen.vert", fragmentShader, constants_);
    engine_.noteSources(prog);  // its stubs are named too
    prog.use();
    engine_.setPassUniforms(prog, scene_, pass_, inputs_);
    program_ = &prog;
    return prog;
}

void EngineDrawContext::drawToTarget(int target, glm::ivec2 size) {
    if (target < 0 || target > 1 || size.x < 1 || size.y < 1 || size.x > 16384 || size.y > 16384)
        throw Error("renderer '" + scene_.renderer + "': an intermediate target must be 0 or 1, 1..16384 pixels a side");
    engine_.ensureIntermediate(target, size);
    glBindFramebuffer(GL_FRAMEBUFFER, engine_.intermediate_[target].framebuffer);
    glViewport(0, 0, size.x, size.y);
    glDisable(GL_BLEND);  // a pass writes its target whole
}

void EngineDrawContext::clearTarget(glm::vec4 colour) {
    glClearColor(colour.r, colour.g, colour.b, colour.a);
    glClear(GL_COLOR_BUFFER_BIT);
}

void EngineDrawContext::bindTargetTexture(int target, int unit) {
    if (target < 0 || target > 1 || !engine_.intermediate_[target].color)
        throw Error("renderer '" + scene_.renderer + "': intermediate target " + std::to_string(target) + " was never drawn");
    glActiveTexture(GL_TEXTURE0 + GLenum(unit));
    glBindTexture(GL_TEXTURE_2D, engine_.intermediate_[target].color);
}

void EngineDrawContext::drawToOutput() {
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(outputFramebuffer_));
    glViewport(outputViewport_[0], outputViewport_[1], outputViewport_[2], outputViewport_[3]);
    glEnable(GL_BLEND);  // as the object-order pass began: "over", premultiplied
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

void EngineDrawContext::drawFullScreen() {
    glBindVertexArray(engine_.vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (strictGlChecks()) checkGlDraw(("drawing a pass of renderer '" + scene_.renderer + "'").c_str());
}

}  // namespace voxlab
