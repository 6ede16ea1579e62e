// voxlab stage texslice2d: renderer "texslice2d": object-order volume rendering with three
// stacks of axis-aligned 2D slices (the first GPU volume renderers).
#include <cmath>

#include "voxlab/camera.h"
#include "voxlab/slice_axis.h"
#include "voxlab/stage_library.h"
#include "voxlab/renderers.h"
#include "voxlab/shader.h"
#include "voxlab/volume.h"

namespace voxlab {

// Object-order renderers: they draw proxy geometry (draw()) instead of
// casting rays.
class Texslice2dRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool objectOrder() const override { return true; }
    bool needsTransferFunction() const override { return true; }
    void draw(DrawContext& context, const ParameterValues& values) const override;
};

namespace {
constexpr int kStackUnit = 4;  // texture unit of the slice stack
}

std::string Texslice2dRenderer::id() const { return "texslice2d"; }

std::string Texslice2dRenderer::description() const {
    return "2D texture slicing: the axis-aligned slice stack facing the viewer, blended back to front";
}

std::vector<ParameterSpec> Texslice2dRenderer::parameters() const {
    return {{"slices_per_voxel", ParameterType::Int, 1, 8, 1,
             "slices per voxel layer; in-between slices blend the two nearest layers"},
            {"wireframe", ParameterType::Bool, 0, 1, 0, "outline every n-th slice drawn, about 24 per stack at any step (lecture demo)"}};
}

void Texslice2dRenderer::draw(DrawContext& ctx, const ParameterValues& values) const {
    const Volume& v = ctx.volume();
    const glm::dvec3 ext = v.extent(), forward = ctx.camera().forward;
    const int a = cppStages().chooseSliceAxis(forward), b = (a + 1) % 3, c = (a + 2) % 3;
    const int perVoxel = int(values.at("slices_per_voxel"));
    const int count = v.dims()[a] * perVoxel;
    const double spacing = v.spacing()[a] / perVoxel;
    ctx.bindSliceStack(a, kStackUnit);
    ctx.program().set("u_stack", kStackUnit);
    ctx.program().set("u_stack_axis", a);
    ctx.program().set("u_slice_spacing", float(spacing));

    // Slice k sits at (k + 1/2) * spacing along the axis (voxel centres when
    // perVoxel is 1). Back to front: the far end first.
    std::vector<std::vector<glm::dvec3>> quads;
    for (int i = 0; i < count; ++i) {
        const int k = forward[a] > 0.0 ? count - 1 - i : i;
        std::vector<glm::dvec3> q(4);
        for (int corner = 0; corner < 4; ++corner) {
            q[corner][a] = (k + 0.5) * spacing;
            q[corner][b] = (corner == 1 || corner == 2) ? ext[b] : 0.0;
            q[corner][c] = corner >= 2 ? ext[c] : 0.0;
        }
        quads.push_back(q);
    }
    drawSlicePolygons(ctx, quads, values.at("wireframe") != 0.0);
}

}  // namespace voxlab

VOXLAB_RENDERERS(texslice2d) { registry.add<voxlab::Texslice2dRenderer>(); }
