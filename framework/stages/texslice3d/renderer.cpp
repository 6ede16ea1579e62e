// voxlab stage texslice3d: renderer "texslice3d": object-order volume rendering with
// view-aligned slices through the 3D texture.
#include <cmath>

#include "voxlab/camera.h"
#include "voxlab/proxy_geometry.h"
#include "voxlab/stage_library.h"
#include "voxlab/renderers.h"
#include "voxlab/shader.h"
#include "voxlab/volume.h"

namespace voxlab {

class Texslice3dRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool objectOrder() const override { return true; }
    bool needsTransferFunction() const override { return true; }
    void draw(DrawContext& context, const ParameterValues& values) const override;
};

std::string Texslice3dRenderer::id() const { return "texslice3d"; }

std::string Texslice3dRenderer::description() const {
    return "3D texture slicing: view-aligned polygons through the 3D texture, blended back to front";
}

std::vector<ParameterSpec> Texslice3dRenderer::parameters() const {
    std::vector<ParameterSpec> p = {
        {"wireframe", ParameterType::Bool, 0, 1, 0, "outline every n-th proxy polygon, about 24 across the box at any step (lecture demo)"}};
    for (ParameterSpec& s : shadingParameters(false)) p.push_back(s);
    return p;
}

void Texslice3dRenderer::draw(DrawContext& ctx, const ParameterValues& values) const {
    const Volume& v = ctx.volume();
    const glm::dvec3 ext = v.extent(), n = ctx.camera().forward;
    const double step = ctx.scene().step * v.minSpacing();
    // The planes dot(n, p) = d cover the box's extent along n, from its
    // nearest corner to its farthest, `step` apart and starting half a step
    // in (as ray samples do).
    double nearest = 1e300, farthest = -1e300;
    for (int bits = 0; bits < 8; ++bits) {
        const glm::dvec3 corner(bits & 1 ? ext.x : 0.0, bits & 2 ? ext.y : 0.0, bits & 4 ? ext.z : 0.0);
        nearest = std::min(nearest, glm::dot(n, corner));
        farthest = std::max(farthest, glm::dot(n, corner));
    }
    const int count = int(std::floor((farthest - nearest) / step + 0.5));
    std::vector<std::vector<glm::dvec3>> polygons;
    for (int k = count - 1; k >= 0; --k)  // back to front
        polygons.push_back(cppStages().planeBoxPolygon(n, nearest + (k + 0.5) * step, glm::dvec3(0.0), ext));
    drawSlicePolygons(ctx, polygons, values.at("wireframe") != 0.0);
}

}  // namespace voxlab

VOXLAB_RENDERERS(texslice3d) { registry.add<voxlab::Texslice3dRenderer>(); }
