// voxlab: the render engine's side of empty-space skipping (see
// empty_space.h and shaders/voxlab/empty_space.glsl).
#include <algorithm>

#include "voxlab/render_engine.h"
#include "voxlab_gl.h"

namespace voxlab {
namespace {
constexpr int kBrickUnit = 5;  // after the cutting plane's layers (3 and 4)
}

void RenderEngine::bindBricks(const ShaderProgram& prog, const EmptySpaceRule& rule, const TransferFunctionTable* table,
                              const std::vector<Tf2dWidget>& widgets) {
    bool upload = false;
    if (!bricks_ || bricksGeneration_ != volumeGeneration_) {
        bricks_ = std::make_unique<BrickGrid>(BrickGrid::build(*volume_));
        bricksGeneration_ = volumeGeneration_;
        brickTexels_.assign(bricks_->brickCount(), glm::vec4(0.0f));
        for (std::size_t i = 0; i < brickTexels_.size(); ++i)
            brickTexels_[i] = glm::vec4(bricks_->range[i], -1.0f, 0.0f);  // -1: not yet classified
        brickTexture_.ensure();
        upload = true;
    }
    std::vector<std::uint8_t> visible;
    switch (rule.kind) {
        case EmptySpaceRule::Kind::TransferFunction:
            visible = table ? visibleBricks(*bricks_, *table) : allBricksVisible(*bricks_);
            break;
        case EmptySpaceRule::Kind::TransferFunction2D:
            if (bricks_->gradientBound.empty()) bricks_->computeGradientBounds(*volume_);  // once per volume
            visible = visibleBricks(*bricks_, widgets);
            break;
        case EmptySpaceRule::Kind::AtLeast: visible = bricksReaching(*bricks_, rule.threshold); break;
        case EmptySpaceRule::Kind::None: visible = allBricksVisible(*bricks_); break;
    }
    // Re-upload only when a flag changed (a new transfer function, another
    // renderer): while the camera moves, the texture stays as it is.
    for (std::size_t i = 0; i < visible.size(); ++i) {
        const float flag = visible[i] ? 1.0f : 0.0f;
        if (brickTexels_[i].b != flag) brickTexels_[i].b = flag, upload = true;
    }
    glActiveTexture(GL_TEXTURE0 + kBrickUnit);
    glBindTexture(GL_TEXTURE_3D, brickTexture_);
    if (upload) {
        const glm::ivec3 n = bricks_->count;
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA32F, n.x, n.y, n.z, 0, GL_RGBA, GL_FLOAT, brickTexels_.data());
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        checkGlError("uploading the brick grid");
    }
    prog.set("u_bricks", kBrickUnit);
    prog.set("u_brick_extent", glm::vec3(double(bricks_->brickSize) * volume_->spacing()));
    prog.set("u_brick_count", bricks_->count);
}

}  // namespace voxlab
