// voxlab internals: the render engine's side of DrawContext (renderer.h),
// what object-order renderers draw with. One dynamic vertex buffer of world
// positions (attribute 0), instanced squares, the slice stacks, a depth
// test, and full-screen passes into two float targets (multi-pass
// renderers: shear-warp's intermediate image).
#pragma once

#include <string>
#include <vector>

#include "voxlab/render_engine.h"
#include "voxlab/renderer.h"

namespace voxlab {

class EngineDrawContext final : public DrawContext {
public:
    // `pass`, `inputs` and `constants` are the engine's for this pass: they
    // set up every program the renderer asks for the same way.
    EngineDrawContext(RenderEngine& engine, const Scene& scene, const Camera& camera, const ShaderProgram& program,
                      const RenderEngine::Pass& pass, const RenderEngine::PassInputs& inputs,
                      const ShaderConstants& constants);

    const Scene& scene() const override { return scene_; }
    const Volume& volume() const override;
    const Camera& camera() const override { return camera_; }
    const ShaderProgram& program() const override { return *program_; }
    const TransferFunction& transferFunction() const override;
    void drawTriangles(const std::vector<glm::vec3>& vertices) override;
    void drawFacets(const std::vector<glm::vec3>& vertices) override;
    void drawLines(const std::vector<glm::vec3>& vertices) override;
    void drawInstancedSquares(const std::vector<glm::vec4>& instances) override;
    void enableDepthTest() override;
    void bindSliceStack(int axis, int unit) override;
    const ShaderProgram& useFullScreenProgram(const std::string& fragmentShader) override;
    void drawToTarget(int target, glm::ivec2 size) override;
    void clearTarget(glm::vec4 colour) override;
    void bindTargetTexture(int target, int unit) override;
    void drawToOutput() override;
    void drawFullScreen() override;

private:
    void drawArrays(unsigned mode, const std::vector<glm::vec3>& vertices,
                    const std::vector<glm::vec3>* faceNormals = nullptr);

    RenderEngine& engine_;
    const Scene& scene_;
    const Camera& camera_;
    const ShaderProgram* program_;
    const RenderEngine::Pass& pass_;
    const RenderEngine::PassInputs& inputs_;
    const ShaderConstants& constants_;
    int outputFramebuffer_ = 0;
    int outputViewport_[4] = {0, 0, 0, 0};
};

}  // namespace voxlab
