// voxlab stage marching_cubes: renderer "mesh": the isosurface as triangles, by marching cubes
// (marching_cubes.h), shaded as iso shades its surface so that the two can
// be held against each other (docs/object_order.md).
#include "voxlab/marching_cubes.h"
#include "voxlab/renderers.h"
#include "voxlab/shader.h"
#include "voxlab/stage_library.h"
#include "voxlab/volume.h"

namespace voxlab {

// The isosurface as a triangle mesh, by marching cubes on the CPU
// (marching_cubes.h; the marching_cubes stage), drawn with a depth test.
// The mesh is kept while the volume, the isovalue and the stage's
// functions stay the same.
class MeshRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::string fragmentShader() const override { return "stages/marching_cubes/mesh.frag"; }
    std::vector<ParameterSpec> parameters() const override;
    bool objectOrder() const override { return true; }
    bool usesTransferFunction() const override { return false; }
    void draw(DrawContext& context, const ParameterValues& values) const override;

private:
    struct Cached;
    std::shared_ptr<const Cached> meshFor(const Volume& volume, double isovalue) const;
    mutable std::shared_ptr<const Cached> cached_;
    mutable std::mutex mutex_;
};

struct MeshRenderer::Cached {
    // What the mesh was made from: the volume's data (address, size, shape),
    // the isovalue and the stage's two functions.
    const void* data = nullptr;
    std::size_t voxels = 0;
    glm::ivec3 dims{0};
    glm::dvec3 spacing{0.0};
    double isovalue = 0.0;
    const void* cubeCase = nullptr;
    const void* edgeCrossing = nullptr;
    std::vector<glm::vec3> triangles, edges;  // 3 and 2 world positions each
};

// The parameters the C++ side reads (the rest reach the shader as uniforms).
constexpr const char* kIsovalue = "isovalue";
constexpr const char* kWireframe = "wireframe";

std::string MeshRenderer::id() const { return "mesh"; }

std::string MeshRenderer::description() const {
    return "marching cubes: the isosurface as a triangle mesh made on the CPU, drawn with a depth test";
}

std::vector<ParameterSpec> MeshRenderer::parameters() const {
    using T = ParameterType;
    ParameterSpec isovalue{kIsovalue, T::Float, 0.0, 1.0, 0.5, "the surface's value (data units; default: mid-range)"};
    isovalue.dataUnits = true;
    std::vector<ParameterSpec> p = {
        isovalue,
        {"color_r", T::Float, 0, 1, 0.9, "surface colour, red"},
        {"color_g", T::Float, 0, 1, 0.85, "surface colour, green"},
        {"color_b", T::Float, 0, 1, 0.75, "surface colour, blue"},
        {"depth", T::Bool, 0, 1, 0, "show the surface's depth (near white, far black), as iso does"},
        {"flat", T::Bool, 0, 1, 0, "shade each triangle by its own normal: the facets marching cubes made"},
        {kWireframe, T::Bool, 0, 1, 0, "draw the triangles' edges over the surface"},
    };
    for (ParameterSpec& s : shadingParameters(true)) p.push_back(s);
    return p;
}

std::shared_ptr<const MeshRenderer::Cached> MeshRenderer::meshFor(const Volume& volume, double isovalue) const {
    const CppStages& stage = cppStages();
    const void* cube = reinterpret_cast<const void*>(stage.cubeCase);
    const void* edge = reinterpret_cast<const void*>(stage.edgeCrossing);
    std::lock_guard<std::mutex> lock(mutex_);
    if (cached_ && cached_->data == volume.data() && cached_->voxels == volume.voxelCount() &&
        cached_->dims == volume.dims() && cached_->spacing == volume.spacing() && cached_->isovalue == isovalue &&
        cached_->cubeCase == cube && cached_->edgeCrossing == edge)
        return cached_;
    auto made = std::make_shared<Cached>();
    made->data = volume.data(), made->voxels = volume.voxelCount(), made->dims = volume.dims();
    made->spacing = volume.spacing(), made->isovalue = isovalue, made->cubeCase = cube, made->edgeCrossing = edge;
    const TriangleMesh mesh = extractIsosurface(volume, isovalue);
    made->triangles.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            made->triangles.push_back(mesh.vertices[t[std::size_t(k)]]);
            made->edges.push_back(mesh.vertices[t[std::size_t(k)]]);
            made->edges.push_back(mesh.vertices[t[std::size_t((k + 1) % 3)]]);
        }
    cached_ = made;
    return made;
}

void MeshRenderer::draw(DrawContext& ctx, const ParameterValues& values) const {
    const std::shared_ptr<const Cached> mesh = meshFor(ctx.volume(), values.at(kIsovalue));
    ctx.enableDepthTest();
    ctx.program().set("u_mesh_lines", 0);
    ctx.drawFacets(mesh->triangles);
    if (values.at(kWireframe) != 0.0) {
        ctx.program().set("u_mesh_lines", 1);
        ctx.drawLines(mesh->edges);
    }
}

}  // namespace voxlab

VOXLAB_RENDERERS(marching_cubes) { registry.add<voxlab::MeshRenderer>(); }
