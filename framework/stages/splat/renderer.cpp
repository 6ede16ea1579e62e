// voxlab stage splat: renderer "splat": splatting (splatting.h), object order: every
// voxel the transfer function shows, thrown at the image as a Gaussian
// footprint, back to front in the order of the splat stage's walk.
#include <cstring>

#include "voxlab/camera.h"
#include "voxlab/renderers.h"
#include "voxlab/shader.h"
#include "voxlab/splatting.h"
#include "voxlab/stage_library.h"
#include "voxlab/volume.h"

namespace voxlab {

// Splatting (splatting.h): every voxel the transfer function shows, drawn as
// a Gaussian footprint (a point sprite), back to front in the splat stage's
// order. The points are kept while the volume, the transfer function and
// the walk stay the same.
class SplatRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool objectOrder() const override { return true; }
    bool needsTransferFunction() const override { return true; }
    std::string vertexShader() const override { return "stages/splat/splat.vert"; }
    void draw(DrawContext& context, const ParameterValues& values) const override;

private:
    struct Cached;
    std::shared_ptr<const Cached> pointsFor(const Volume& volume, const TransferFunction& tf, glm::dvec3 view) const;
    mutable std::shared_ptr<const Cached> cached_;
    mutable std::mutex mutex_;
};

namespace {
constexpr double kCutoff = 3.0;  // footprints end at 3 standard deviations (1.1% of the matter left out)
}

struct SplatRenderer::Cached {
    // What the points were made from: the volume's data, the transfer
    // function, the walk and the function that gave it.
    const void* data = nullptr;
    std::size_t voxels = 0;
    std::vector<ControlPoint> function;
    std::array<int, 3> axes{}, step{};
    const void* order = nullptr;
    std::vector<glm::vec4> points;
};

std::string SplatRenderer::id() const { return "splat"; }

std::string SplatRenderer::description() const {
    return "splatting: each visible voxel a Gaussian footprint on the image, back to front";
}

std::vector<ParameterSpec> SplatRenderer::parameters() const {
    return {{"radius", ParameterType::Float, 0.3, 3.0, 0.7,
             "the kernel's standard deviation, in smallest spacings (larger: blurrier, fewer gaps)"}};
}

std::shared_ptr<const SplatRenderer::Cached> SplatRenderer::pointsFor(const Volume& volume, const TransferFunction& tf,
                                                                       glm::dvec3 viewDirection) const {
    const CppStages& stage = cppStages();
    const SplatOrder order = stage.splatOrder(viewDirection);
    std::lock_guard<std::mutex> lock(mutex_);
    if (cached_ && cached_->data == volume.data() && cached_->voxels == volume.voxelCount() &&
        cached_->function == tf.points() && cached_->axes == order.axes && cached_->step == order.step &&
        cached_->order == reinterpret_cast<const void*>(stage.splatOrder))
        return cached_;
    auto made = std::make_shared<Cached>();
    made->data = volume.data(), made->voxels = volume.voxelCount(), made->function = tf.points();
    made->axes = order.axes, made->step = order.step, made->order = reinterpret_cast<const void*>(stage.splatOrder);
    made->points = splatPoints(volume, tf, order);
    cached_ = made;
    return made;
}

void SplatRenderer::draw(DrawContext& ctx, const ParameterValues& values) const {
    const Volume& v = ctx.volume();
    const std::shared_ptr<const Cached> splats = pointsFor(v, ctx.transferFunction(), ctx.camera().forward);
    const glm::dvec3 s = v.spacing();
    ctx.program().set("u_splat_sigma", float(values.at("radius") * v.minSpacing()));
    ctx.program().set("u_splat_cutoff", float(kCutoff));
    ctx.program().set("u_voxel_volume", float(s.x * s.y * s.z));
    ctx.drawInstancedSquares(splats->points);
}

}  // namespace voxlab

VOXLAB_RENDERERS(splat) { registry.add<voxlab::SplatRenderer>(); }
