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
    const int size = skippingBrickSize(rule, volume_->dims());
    SkipGrid& s = skipGrids_[size == kBrickSize ? 0 : 1];
    bool upload = false;
    if (!s.grid || s.generation != volumeGeneration_ || s.grid->brickSize != size) {
        s.grid = std::make_unique<BrickGrid>(BrickGrid::build(*volume_, size));
        s.generation = volumeGeneration_;
        s.texels.assign(s.grid->brickCount(), glm::vec4(0.0f));
        for (std::size_t i = 0; i < s.texels.size(); ++i)
            s.texels[i] = glm::vec4(s.grid->range[i], -1.0f, 0.0f);  // -1: not yet classified
        s.texture.ensure();
        upload = true;
    }
    BrickGrid& grid = *s.grid;
    std::vector<std::uint8_t> visible;
    switch (rule.kind) {
        case EmptySpaceRule::Kind::TransferFunction:
            visible = table ? visibleBricks(grid, *table) : allBricksVisible(grid);
            break;
        case EmptySpaceRule::Kind::TransferFunction2D:
            // Once per volume and estimator.
            if (grid.gradientBound.empty() || grid.boundsFor != rule.gradients)
                grid.computeGradientBounds(*volume_, rule.gradients);
            visible = visibleBricks(grid, widgets, rule.gradientBoundScale);
            break;
        case EmptySpaceRule::Kind::AtLeast: visible = bricksReaching(grid, rule.threshold); break;
        case EmptySpaceRule::Kind::None: visible = allBricksVisible(grid); break;
    }
    // Re-upload only when a flag changed (a new transfer function, another
    // renderer): while the camera moves, the texture stays as it is.
    for (std::size_t i = 0; i < visible.size(); ++i) {
        const float flag = visible[i] ? 1.0f : 0.0f;
        if (s.texels[i].b != flag) s.texels[i].b = flag, upload = true;
    }
    glActiveTexture(GL_TEXTURE0 + kBrickUnit);
    glBindTexture(GL_TEXTURE_3D, s.texture);
    if (upload) {
        const glm::ivec3 n = grid.count;
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA32F, n.x, n.y, n.z, 0, GL_RGBA, GL_FLOAT, s.texels.data());
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        checkGlError("uploading the brick grid");
    }
    skipping_ = &s;
    prog.set("u_bricks", kBrickUnit);
    prog.set("u_brick_extent", glm::vec3(double(grid.brickSize) * volume_->spacing()));
    prog.set("u_brick_count", grid.count);
}

}  // namespace voxlab
