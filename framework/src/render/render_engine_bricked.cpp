// voxlab: the render engine's side of bricked rendering (see
// voxlab/volume_bricks.h and shaders/voxlab/bricks.glsl).
//
// A bricked pass draws the full-screen triangle once per brick, front to
// back, into two float targets taking turns: each pass reads the state the
// one before it wrote and writes the state with its brick's part added, for
// every pixel (a pixel whose ray misses the brick copies the state on). A
// resolve pass then turns the state into the image in the target the pass
// was drawing to. Combines that do not depend on the order (a largest or
// smallest value, a sum) draw the bricks already on the GPU first, so that
// a pool smaller than the volume uploads fewer of them.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include <unistd.h>

#include "engine_internal.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/gl_context.h"
#include "voxlab/render_engine.h"
#include "volume_textures.h"
#include "voxlab_gl.h"

namespace voxlab {

namespace {

// GL_NVX_gpu_memory_info and GL_ATI_meminfo (values from their specs).
constexpr GLenum kNvxTotalAvailableKiB = 0x9048;
constexpr GLenum kAtiTextureFreeMemory = 0x87FC;

bool hasExtension(const std::string& name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && name == e) return true;
    }
    return false;
}

std::string mib(std::size_t bytes) { return std::to_string((bytes + (1u << 19)) >> 20) + " MiB"; }

std::string describe(const BrickLayout& layout) {
    const glm::ivec3 n = layout.count;
    return std::to_string(n.x) + "x" + std::to_string(n.y) + "x" + std::to_string(n.z) + " bricks for a " +
           mib(layout.budgetBytes) + " GPU memory budget";
}

bool orderFree(BrickCombine combine) {
    return combine == BrickCombine::Largest || combine == BrickCombine::Smallest || combine == BrickCombine::Sum;
}

// Whether some ray of the view can enter the world box [lo, hi]: not when
// all its corners lie beyond one side of the image (with a pixel to spare)
// or, in perspective, behind the eye.
bool inView(const Camera& cam, const glm::dvec3& lo, const glm::dvec3& hi) {
    const bool perspective = cam.projection == Projection::Perspective;
    const double halfW = cam.pixelScale * (0.5 * cam.width + 1.0), halfH = cam.pixelScale * (0.5 * cam.height + 1.0);
    int beyond[5] = {0, 0, 0, 0, 0};  // right, left, below, above, behind
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
        const glm::dvec3 q = p - cam.position;
        const double u = glm::dot(q, cam.right), v = glm::dot(q, cam.down);
        const double d = perspective ? glm::dot(q, cam.forward) : 1.0;
        beyond[0] += u > halfW * d, beyond[1] += u < -halfW * d;
        beyond[2] += v > halfH * d, beyond[3] += v < -halfH * d;
        beyond[4] += perspective && d < 0.0;
    }
    return std::none_of(std::begin(beyond), std::end(beyond), [](int n) { return n == 8; });
}

}  // namespace

// A brick's pass changes no pixel when no ray of the view enters its box,
// or, with empty-space skipping, when every brick of the skipping grid in it
// is empty for the pass's classification (its rays then leap over all of
// its samples and pass the state on unchanged).
bool RenderEngine::brickNeeded(int brick, const Camera& cam, bool skipping) const {
    const VolumeBrick& b = volumeTextures_->layout().bricks[std::size_t(brick)];
    const glm::dvec3 spacing = volume_->spacing();
    if (!inView(cam, glm::dvec3(b.lo) * spacing, glm::dvec3(b.hi) * spacing)) return false;
    if (!skipping || !skipping_) return true;
    const BrickGrid& grid = *skipping_->grid;
    // One cell more on each side: a sample on the brick's face, placed in
    // float, may be looked up in the cell beyond it.
    const glm::ivec3 from = glm::max(b.lo / grid.brickSize - 1, glm::ivec3(0));
    const glm::ivec3 to = glm::min((b.hi - 1) / grid.brickSize + 1, grid.count - 1);
    for (int z = from.z; z <= to.z; ++z)
        for (int y = from.y; y <= to.y; ++y)
            for (int x = from.x; x <= to.x; ++x)
                if (skipping_->texels[grid.index({x, y, z})].b != 0.0f) return true;
    return false;
}

bool softwareRenderer() {
    const std::string name = currentGlRenderer();
    return name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos;
}

// Three quarters of what the driver says is free, for the volume leaves
// room for the targets and tables. A software renderer's textures are a
// second copy of the volume in the machine's own memory: at most 256 MiB
// of them (and at most a quarter of the memory), so that a large volume
// costs its own size and 256 MiB, drawn in bricks, rather than twice its
// size. Other drivers that say nothing: 1 GiB.
std::size_t driverGpuMemoryBudget() {
    GLint kib[4] = {0, 0, 0, 0};
    if (hasExtension("GL_NVX_gpu_memory_info")) {
        glGetIntegerv(kNvxTotalAvailableKiB, kib);
        if (kib[0] > 0) return std::size_t(kib[0]) * 1024 / 4 * 3;
    }
    if (hasExtension("GL_ATI_meminfo")) {
        glGetIntegerv(kAtiTextureFreeMemory, kib);
        if (kib[0] > 0) return std::size_t(kib[0]) * 1024 / 4 * 3;
    }
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (softwareRenderer()) {
        const std::size_t software = std::size_t(256) << 20;
        return pages > 0 && page > 0 ? std::min(software, std::size_t(pages) * std::size_t(page) / 4) : software;
    }
    return std::size_t(1) << 30;
}

const BrickLayout& RenderEngine::brickLayout() const { return volumeTextures_->layout(); }

std::size_t RenderEngine::brickUploads() const { return volumeTextures_->uploads(); }

std::size_t RenderEngine::brickBytesUploaded() const { return volumeTextures_->bytesUploaded(); }

std::size_t RenderEngine::budgetFor(const Scene& scene) const {
    return scene.gpuMemoryMiB ? std::size_t(*scene.gpuMemoryMiB * double(1 << 20)) : defaultBudget_;
}

// What a bricked volume can be drawn with: the renderer says how it adds a
// brick's part (or that it cannot); the engine refuses what reads beyond a
// brick's apron or needs a texture of the whole volume.
BrickCombine RenderEngine::checkBricked(const Scene& scene, const Pass& pass) const {
    const BrickLayout& layout = volumeTextures_->layout();
    if (!layout.bricked()) return BrickCombine::None;
    const Renderer& renderer = *pass.renderer;
    const std::string why = " (the volume is cut into " + describe(layout) + ")";
    auto refuse = [&](const std::string& what) {
        throw Error(renderer.id() + ": " + what + " does not combine with a bricked volume" + why);
    };
    if (renderer.objectOrder())
        throw Error(renderer.id() + ": draws the whole volume's slices and does not draw a bricked volume" + why +
                    "; a ray-casting renderer does");
    if (scene.cuttingPlane) refuse("a cutting plane");
    if (scene.labels) refuse("a label map");
    if (scene.fusion) refuse("a fused second volume");
    if (isCubic(scene.interpolation)) refuse("cubic interpolation");
    if (renderer.precomputedGradients(pass.values)) refuse("parameter 'precomputed_gradients'");
    // The crossing test looks one sample back across a brick's face.
    if (renderer.profileModel() == ProfileModel::Isosurface && scene.step > 1.0)
        refuse("a step above 1 (the bricks' apron holds " + std::to_string(kTextureBrickApron) + " voxels)");
    BrickCombine combine = BrickCombine::None;
    try {
        combine = renderer.brickCombine(pass.values);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + why);
    }
    if (combine == BrickCombine::None)
        throw Error(renderer.id() + ": does not draw a bricked volume" + why +
                    ": its value at a sample depends on samples in other bricks");
    return combine;
}

// Binds brick `brick`'s texture (uploading it if it is not resident) and
// says where it lies: the voxels its texture holds, the world box it owns.
void RenderEngine::bindVolumeBrick(int brick, const ShaderProgram& prog, const Scene& scene) {
    glActiveTexture(GL_TEXTURE0 + kVolumeUnit);
    glBindTexture(GL_TEXTURE_3D, volumeTextures_->texture(brick));
    const GLint filter = scene.interpolation == Interpolation::Hardware ? GL_LINEAR : GL_NEAREST;
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, filter);
    const BrickLayout& layout = volumeTextures_->layout();
    if (!layout.bricked()) return;
    const VolumeBrick& b = layout.bricks[std::size_t(brick)];
    prog.set("u_brick_origin", b.textureOrigin);
    prog.set("u_brick_texture_dims", b.textureSize);
    // The faces on the volume's boundary lie far out: samples there are the
    // outer bricks' (the ray is clipped to the box already).
    const glm::dvec3 spacing = volume_->spacing();
    glm::vec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
        lo[a] = b.lo[a] == 0 ? -1e30f : float(double(b.lo[a]) * spacing[a]);
        hi[a] = b.hi[a] == volume_->dims()[a] ? 1e30f : float(double(b.hi[a]) * spacing[a]);
    }
    prog.set("u_brick_lo", lo);
    prog.set("u_brick_hi", hi);
}

void RenderEngine::drawBricked(const Scene& scene, const Pass& pass, const PassInputs& inputs,
                               const ShaderProgram& prog, const ShaderConstants& constants, BrickCombine combine,
                               const std::function<void(const ShaderProgram&)>& prepare) {
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    ensureLayers(scene.width, scene.height);
    const BrickLayout& layout = volumeTextures_->layout();
    const Camera cam = Camera::make(scene.camera, volume_->extent(), scene.width, scene.height);
    std::vector<int> order = frontToBackOrder(layout, cam.position / volume_->spacing(),
                                              cam.forward / volume_->spacing(),
                                              cam.projection == Projection::Orthographic);
    const bool skipping = constants.at("u_skipping") != 0;
    order.erase(std::remove_if(order.begin(), order.end(), [&](int b) { return !brickNeeded(b, cam, skipping); }),
                order.end());
    if (orderFree(combine))
        std::stable_partition(order.begin(), order.end(), [&](int b) { return volumeTextures_->resident(b); });
    volumeTextures_->beginFrame(order);
    bricksDrawn_ += order.size();

    // Counting samples: the state still has to be what a render leaves (the
    // walks skip and stop by it), so each brick is drawn twice: by the
    // render's own program for the state, and by the counting one, reading
    // the same state, whose counts are added up by blending in a third
    // target.
    const ShaderProgram* stateProgram = &prog;
    const ShaderProgram* counter = nullptr;
    if (countingSamples_) {
        ShaderConstants plain = constants;
        plain["u_count_samples"] = 0;
        stateProgram = &program(pass.renderer->vertexShader(), pass.renderer->fragmentShader(), plain);
        prepare(*stateProgram);
        counter = &prog;
        glBindFramebuffer(GL_FRAMEBUFFER, layers_[2].framebuffer);
        glViewport(0, 0, scene.width, scene.height);
        const glm::vec4 zero(0.0f);
        glClearBufferfv(GL_COLOR, 0, &zero[0]);
    }
    // The state before the first brick: nothing seen, or the identity of
    // the running maximum or minimum.
    glm::vec4 start(0.0f);
    if (combine == BrickCombine::Largest) start.x = -3.4e38f;
    if (combine == BrickCombine::Smallest) start.x = 3.4e38f;
    glBindFramebuffer(GL_FRAMEBUFFER, layers_[0].framebuffer);
    glViewport(0, 0, scene.width, scene.height);
    glClearBufferfv(GL_COLOR, 0, &start[0]);
    glDisable(GL_BLEND);
    glBindVertexArray(vao_);
    int current = 0;
    auto drawBrick = [&](const ShaderProgram& p, int b, GLuint fbo) {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glActiveTexture(GL_TEXTURE0 + kLayerUnit);
        glBindTexture(GL_TEXTURE_2D, layers_[current].color);
        p.use();
        p.set("u_brick_state", kLayerUnit);
        bindVolumeBrick(b, p, scene);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    for (int b : order) {
        if (counter) {
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            drawBrick(*counter, b, layers_[2].framebuffer);
            glDisable(GL_BLEND);
        }
        drawBrick(*stateProgram, b, layers_[1 - current].framebuffer);
        current = 1 - current;
    }
    checkGlDraw(("drawing the bricks with renderer '" + pass.renderer->id() + "'").c_str());
    if (counter) current = 2;

    const ShaderConstants resolveConstants = {{"u_brick_combine", int(combine)},
                                              {"u_count_samples", countingSamples_ ? 1 : 0},
                                              {"u_has_tf", constants.at("u_has_tf")},
                                              {"u_layer", 0}};
    const ShaderProgram& resolve = program("voxlab/fullscreen.vert", "voxlab/brick_resolve.frag", resolveConstants);
    noteSources(resolve);
    resolve.use();
    setPassUniforms(resolve, scene, pass, inputs);
    glActiveTexture(GL_TEXTURE0 + kLayerUnit);
    glBindTexture(GL_TEXTURE_2D, layers_[current].color);
    resolve.set("u_brick_state", kLayerUnit);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
    glViewport(0, 0, scene.width, scene.height);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    checkGlDraw("resolving the bricks' state into the image");
}

}  // namespace voxlab
