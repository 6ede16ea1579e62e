// voxlab stage shearwarp: renderer "shearwarp": shear-warp volume rendering (shear_warp.h),
// orthographic views. The shearwarp stage factors the view (C++); the slices
// along the principal axis are composited front to back into an
// intermediate image, one full-screen pass each, two float images taking
// turns (the stage's GLSL lays each slice under the last result); a last
// pass warps the intermediate image onto the screen.
#include <cmath>

#include "voxlab/camera.h"
#include "voxlab/renderers.h"
#include "voxlab/shader.h"
#include "voxlab/shear_warp.h"
#include "voxlab/stage_library.h"
#include "voxlab/volume.h"

namespace voxlab {

// Shear-warp (shear_warp.h), orthographic views: the shearwarp stage's
// factorisation, one full-screen pass per slice into an intermediate image
// (two float targets taking turns), one warp pass onto the screen.
class ShearWarpRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    bool objectOrder() const override { return true; }
    bool needsTransferFunction() const override { return true; }
    std::string vertexShader() const override { return "voxlab/fullscreen.vert"; }
    void checkScene(const Scene& scene, const ParameterValues& values) const override;
    void draw(DrawContext& context, const ParameterValues& values) const override;
};

namespace {
constexpr int kStackUnit = 4, kAccumulatedUnit = 5, kIntermediateUnit = 6;
}

std::string ShearWarpRenderer::id() const { return "shearwarp"; }

std::string ShearWarpRenderer::description() const {
    return "shear-warp: slices sheared to align the rays, composited into an intermediate image, warped to the screen";
}

void ShearWarpRenderer::checkScene(const Scene& scene, const ParameterValues& values) const {
    Renderer::checkScene(scene, values);
    if (scene.camera.projection != Projection::Orthographic)
        throw Error("shearwarp: orthographic views only (the perspective factorisation is not implemented)");
}

void ShearWarpRenderer::draw(DrawContext& ctx, const ParameterValues&) const {
    const Volume& v = ctx.volume();
    const ShearWarp sw = cppStages().factorShearWarp(ctx.camera(), v.dims(), v.spacing());
    if (sw.axis < 0 || sw.axis > 2 || sw.size.x < 1 || sw.size.y < 1 || sw.size.x > 16384 || sw.size.y > 16384)
        throw Error("factorShearWarp gave axis " + std::to_string(sw.axis) + " and an intermediate image of " +
                    std::to_string(sw.size.x) + "x" + std::to_string(sw.size.y));
    const int c = sw.axis, n = v.dims()[c];
    // Along a ray the slices are spacing_c / |forward_c| world units apart.
    const double between = v.spacing()[c] / std::max(std::abs(ctx.camera().forward[c]), 1e-9) / v.minSpacing();
    ctx.bindSliceStack(c, kStackUnit);
    const ShaderProgram& slice = ctx.useFullScreenProgram("stages/shearwarp/shearwarp_slice.frag");
    slice.set("u_stack", kStackUnit);
    slice.set("u_accumulated", kAccumulatedUnit);
    slice.set("u_stack_axis", c);
    slice.set("u_shear", glm::vec2(sw.shear));
    slice.set("u_offset", glm::vec2(sw.offset));
    slice.set("u_slice_units", float(between));
    // The first pass reads an empty image: target 1 cleared, then slices
    // alternate 0, 1, 0, ...
    ctx.drawToTarget(1, sw.size);
    ctx.clearTarget(glm::vec4(0.0f));
    int written = 1;
    const int step = sw.front == 0 ? 1 : -1;
    for (int k = sw.front, done = 0; done < n; k += step, ++done) {
        ctx.bindTargetTexture(written, kAccumulatedUnit);
        written = 1 - written;
        ctx.drawToTarget(written, sw.size);
        slice.set("u_slice", k);
        ctx.drawFullScreen();
    }
    ctx.drawToOutput();
    ctx.bindTargetTexture(written, kIntermediateUnit);
    const ShaderProgram& warp = ctx.useFullScreenProgram(fragmentShader());
    const glm::dmat3 unwarp = glm::inverse(sw.warp);
    glm::mat4 m(1.0f);  // the 2D affine map in x, y and w of a 4x4
    m[0] = glm::vec4(float(unwarp[0][0]), float(unwarp[0][1]), 0.0f, 0.0f);
    m[1] = glm::vec4(float(unwarp[1][0]), float(unwarp[1][1]), 0.0f, 0.0f);
    m[3] = glm::vec4(float(unwarp[2][0]), float(unwarp[2][1]), 0.0f, 1.0f);
    warp.set("u_intermediate", kIntermediateUnit);
    warp.set("u_unwarp", m);
    warp.set("u_intermediate_size", glm::vec2(sw.size));
    ctx.drawFullScreen();
}

}  // namespace voxlab

VOXLAB_RENDERERS(shearwarp) { registry.add<voxlab::ShearWarpRenderer>(); }
