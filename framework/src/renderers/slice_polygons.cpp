// voxlab: drawing the texture slicers' proxy polygons.
#include <algorithm>

#include "voxlab/renderers.h"
#include "voxlab/shader.h"

namespace voxlab {

int outlineStride(std::size_t polygons) {
    return std::max(1, int((polygons + kOutlinedSlices - 1) / kOutlinedSlices));
}

void drawSlicePolygons(DrawContext& ctx, const std::vector<std::vector<glm::dvec3>>& polygons, bool outline) {
    // Convex polygons become triangle fans; one draw call keeps their order,
    // so blending composites them in the order given.
    std::vector<glm::vec3> triangles, edges;
    const std::size_t stride = std::size_t(outlineStride(polygons.size()));
    for (std::size_t k = 0; k < polygons.size(); ++k) {
        const auto& polygon = polygons[k];
        for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
            for (std::size_t j : {std::size_t(0), i, i + 1}) triangles.push_back(glm::vec3(polygon[j]));
        if (k % stride != 0) continue;
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            edges.push_back(glm::vec3(polygon[i]));
            edges.push_back(glm::vec3(polygon[(i + 1) % polygon.size()]));
        }
    }
    ctx.program().set("u_outline", 0);
    ctx.drawTriangles(triangles);
    if (outline) {
        ctx.program().set("u_outline", 1);
        ctx.drawLines(edges);
    }
}

}  // namespace voxlab
