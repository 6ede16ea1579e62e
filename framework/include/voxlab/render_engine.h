// voxlab: the render engine. It owns the GPU side of a scene (the volume
// texture, the transfer-function table, one compiled program per renderer,
// an offscreen float framebuffer) and runs a renderer's shader over every
// pixel. A current GL context (headless or windowed) is required.
//
// Uniforms every renderer can use (see shaders/voxlab/*.glsl):
//   u_volume, u_volume_dims, u_volume_extent, u_value_scale, u_value_offset,
//   u_min_spacing, u_cam_*, u_pixel_scale, u_image_size, u_orthographic,
//   u_step (world units), u_step_units (in smallest spacings), u_window,
//   u_tf, u_tf_range, u_tf_size, u_has_tf, u_background, and u_PARAM for each
//   declared renderer parameter.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "voxlab/image.h"
#include "voxlab/renderer.h"
#include "voxlab/scene.h"
#include "voxlab/shader.h"
#include "voxlab/volume.h"

namespace voxlab {

class RenderEngine {
public:
    // `implementationRoot` is searched first for stage shaders: the project's
    // reference/ by default, or a student's submission folder.
    explicit RenderEngine(std::string implementationRoot = "");
    ~RenderEngine();
    RenderEngine(const RenderEngine&) = delete;
    RenderEngine& operator=(const RenderEngine&) = delete;

    // Uploads the volume as a 3D texture in its native precision (R8, R16,
    // R32F; int16 is shifted by +32768 into R16 so that no value is lost).
    void setVolume(const Volume& volume);
    const Volume* volume() const { return volume_; }

    // Renders `scene` (its dataset is ignored: the volume set above is used)
    // and returns the float image.
    Image render(const Scene& scene);
    // The same into a caller's framebuffer (the viewer's window), at the
    // scene's size, at the given viewport origin.
    void renderTo(const Scene& scene, unsigned framebuffer, int x = 0, int y = 0);
    // Renders into the engine's own float framebuffer and leaves it there
    // (the viewer blits it); offscreenFramebuffer() names it.
    void renderOffscreen(const Scene& scene);
    unsigned offscreenFramebuffer() const { return fbo_; }
    Image readBack() const;

    // Forgets compiled programs so that the next render re-reads the GLSL.
    void reloadShaders();
    const std::string& implementationRoot() const { return implementationRoot_; }

private:
    const ShaderProgram& program(const Renderer& renderer);
    void draw(const Scene& scene, const Renderer& renderer, const ParameterValues& values);
    void uploadTransferFunction(const TransferFunction& tf);
    void ensureTarget(int width, int height);

    std::string implementationRoot_;
    ShaderLibrary library_;
    const Volume* volume_ = nullptr;
    unsigned volumeTexture_ = 0, tfTexture_ = 0, vao_ = 0;
    unsigned fbo_ = 0, colorTexture_ = 0;
    int fboWidth_ = 0, fboHeight_ = 0;
    float valueScale_ = 1.0f, valueOffset_ = 0.0f;
    std::map<std::string, std::unique_ptr<ShaderProgram>> programs_;
    // The uploaded table and what it was baked from (points and value range).
    TransferFunctionTable tfTable_;
    std::vector<ControlPoint> tfPoints_;
    glm::dvec2 tfRange_{0.0};
};

}  // namespace voxlab
