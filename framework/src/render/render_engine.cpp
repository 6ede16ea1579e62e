// voxlab: the render engine (see render_engine.h).
#include "voxlab/render_engine.h"

#include <algorithm>

#include "voxlab/error.h"
#include "voxlab_gl.h"

namespace voxlab {
namespace {

// Texture units used by the framework's GLSL libraries.
constexpr int kVolumeUnit = 0;
constexpr int kTransferFunctionUnit = 1;

}  // namespace

RenderEngine::RenderEngine(std::string implementationRoot)
    : implementationRoot_(implementationRoot.empty() ? projectRoot() + "/reference" : implementationRoot),
      library_(ShaderLibrary::forImplementation(implementationRoot_)) {
    glGenVertexArrays(1, &vao_);  // core profile: drawing needs a bound VAO
    glGenTextures(1, &volumeTexture_);
    glGenTextures(1, &tfTexture_);
    checkGlError("creating the render engine");
}

RenderEngine::~RenderEngine() {
    programs_.clear();
    glDeleteVertexArrays(1, &vao_);
    glDeleteTextures(1, &volumeTexture_);
    glDeleteTextures(1, &tfTexture_);
    if (fbo_) glDeleteFramebuffers(1, &fbo_);
    if (colorTexture_) glDeleteTextures(1, &colorTexture_);
}

void RenderEngine::setVolume(const Volume& volume) {
    const glm::ivec3 d = volume.dims();
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
    if (d.x > maxSize || d.y > maxSize || d.z > maxSize)
        throw Error(volume.name() + ": dimensions exceed this GPU's 3D texture limit of " +
                    std::to_string(maxSize));
    glBindTexture(GL_TEXTURE_3D, volumeTexture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // The shader reads texel t in [0,1] and recovers the data value as
    // t*scale + offset, so every renderer works in the data's own units.
    switch (volume.type()) {
        case VoxelType::UInt8:
            glTexImage3D(GL_TEXTURE_3D, 0, GL_R8, d.x, d.y, d.z, 0, GL_RED, GL_UNSIGNED_BYTE, volume.data());
            valueScale_ = 255.0f, valueOffset_ = 0.0f;
            break;
        case VoxelType::UInt16:
            glTexImage3D(GL_TEXTURE_3D, 0, GL_R16, d.x, d.y, d.z, 0, GL_RED, GL_UNSIGNED_SHORT, volume.data());
            valueScale_ = 65535.0f, valueOffset_ = 0.0f;
            break;
        case VoxelType::Int16: {
            // R16_SNORM would merge -32768 and -32767; shifting keeps every value.
            std::vector<std::uint16_t> shifted(volume.voxelCount());
            const auto* src = static_cast<const std::int16_t*>(volume.data());
            for (std::size_t i = 0; i < shifted.size(); ++i) shifted[i] = std::uint16_t(int(src[i]) + 32768);
            glTexImage3D(GL_TEXTURE_3D, 0, GL_R16, d.x, d.y, d.z, 0, GL_RED, GL_UNSIGNED_SHORT, shifted.data());
            valueScale_ = 65535.0f, valueOffset_ = -32768.0f;
            break;
        }
        case VoxelType::Float32:
            glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, d.x, d.y, d.z, 0, GL_RED, GL_FLOAT, volume.data());
            valueScale_ = 1.0f, valueOffset_ = 0.0f;
            break;
    }
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    checkGlError("uploading the volume texture");
    volume_ = &volume;
}

void RenderEngine::uploadTransferFunction(const TransferFunction& tf) {
    const glm::dvec2 range(volume_->minValue(), volume_->maxValue());
    if (tfTable_.size > 0 && tf.points() == tfPoints_ && range == tfRange_) return;  // still right
    // The table spans the data's value range; bake() sizes it so that linear
    // interpolation stays within half a grey level of the exact function.
    tfTable_ = tf.bake(range.x, range.y);
    // Row-major in a 2D texture (see transfer_function.h); the shader
    // fetches and interpolates entries itself, so no filtering here.
    const int width = std::min(tfTable_.size, kTransferFunctionRowLength);
    const int rows = (tfTable_.size + width - 1) / width;
    std::vector<glm::vec4> texels(std::size_t(width) * rows, tfTable_.rgba.back());
    std::copy(tfTable_.rgba.begin(), tfTable_.rgba.end(), texels.begin());
    glBindTexture(GL_TEXTURE_2D, tfTexture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, rows, 0, GL_RGBA, GL_FLOAT, texels.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGlError("uploading the transfer function");
    tfPoints_ = tf.points();
    tfRange_ = range;
}

const ShaderProgram& RenderEngine::program(const Renderer& renderer) {
    auto it = programs_.find(renderer.id());
    if (it == programs_.end())
        it = programs_
                 .emplace(renderer.id(), std::make_unique<ShaderProgram>(library_, "voxlab/fullscreen.vert",
                                                                          renderer.fragmentShader()))
                 .first;
    return *it->second;
}

void RenderEngine::reloadShaders() { programs_.clear(); }

void RenderEngine::ensureTarget(int width, int height) {
    if (fbo_ && width == fboWidth_ && height == fboHeight_) return;
    if (!fbo_) {
        glGenFramebuffers(1, &fbo_);
        glGenTextures(1, &colorTexture_);
    }
    // A float target: the image is read back unrounded, and the one rounding
    // to 8 bits happens on the CPU by the README's rule.
    glBindTexture(GL_TEXTURE_2D, colorTexture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colorTexture_, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("OpenGL: the float framebuffer (" + std::to_string(width) + "x" + std::to_string(height) +
                    ") is not complete");
    fboWidth_ = width, fboHeight_ = height;
}

void RenderEngine::draw(const Scene& scene, const Renderer& renderer, const ParameterValues& values) {
    const Volume& vol = *volume_;
    const ShaderProgram& prog = program(renderer);
    prog.use();

    glActiveTexture(GL_TEXTURE0 + kVolumeUnit);
    glBindTexture(GL_TEXTURE_3D, volumeTexture_);
    const GLint filter = scene.interpolation == Interpolation::Nearest ? GL_NEAREST : GL_LINEAR;
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, filter);
    prog.set("u_volume", kVolumeUnit);
    prog.set("u_volume_dims", vol.dims());
    prog.set("u_volume_extent", glm::vec3(vol.extent()));
    prog.set("u_value_scale", valueScale_);
    prog.set("u_value_offset", valueOffset_);
    prog.set("u_min_spacing", float(vol.minSpacing()));

    const Camera cam = Camera::make(scene.camera, vol.extent(), scene.width, scene.height);
    prog.set("u_cam_position", glm::vec3(cam.position));
    prog.set("u_cam_forward", glm::vec3(cam.forward));
    prog.set("u_cam_right", glm::vec3(cam.right));
    prog.set("u_cam_down", glm::vec3(cam.down));
    prog.set("u_pixel_scale", float(cam.pixelScale));
    prog.set("u_image_size", glm::vec2(scene.width, scene.height));
    prog.set("u_orthographic", cam.projection == Projection::Orthographic ? 1 : 0);

    prog.set("u_step", float(scene.step * vol.minSpacing()));
    prog.set("u_step_units", float(scene.step));
    const glm::dvec2 window = scene.window.value_or(glm::dvec2(vol.minValue(), vol.maxValue()));
    prog.set("u_window", glm::vec2(window));
    prog.set("u_background", scene.background);

    prog.set("u_has_tf", scene.transferFunction ? 1 : 0);
    if (scene.transferFunction) {
        uploadTransferFunction(*scene.transferFunction);
        prog.set("u_tf_range", glm::vec2(float(tfTable_.lo), float(tfTable_.hi)));
        prog.set("u_tf_size", tfTable_.size);
    }
    glActiveTexture(GL_TEXTURE0 + kTransferFunctionUnit);
    glBindTexture(GL_TEXTURE_2D, tfTexture_);
    prog.set("u_tf", kTransferFunctionUnit);

    renderer.setUniforms(prog, values);

    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    checkGlError(("drawing with renderer '" + renderer.id() + "'").c_str());
}

void RenderEngine::renderTo(const Scene& scene, unsigned framebuffer, int x, int y) {
    if (!volume_) throw Error("render: no volume has been set");
    const Renderer& renderer = rendererRegistry().get(scene.renderer);
    const ParameterValues values = renderer.resolveParameters(scene.parameters);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(x, y, scene.width, scene.height);
    draw(scene, renderer, values);
}

void RenderEngine::renderOffscreen(const Scene& scene) {
    ensureTarget(scene.width, scene.height);
    renderTo(scene, fbo_);
}

Image RenderEngine::render(const Scene& scene) {
    renderOffscreen(scene);
    return readBack();
}

Image RenderEngine::readBack() const {
    const int width = fboWidth_, height = fboHeight_;
    Image image(width, height);
    std::vector<float> rows(image.rgba.size());
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rows.data());
    checkGlError("reading back the image");
    // GL's rows run bottom-up; images run top-down.
    const std::size_t rowFloats = std::size_t(width) * 4;
    for (int y = 0; y < height; ++y)
        std::copy_n(&rows[std::size_t(height - 1 - y) * rowFloats], rowFloats, &image.rgba[y * rowFloats]);
    return image;
}

}  // namespace voxlab
