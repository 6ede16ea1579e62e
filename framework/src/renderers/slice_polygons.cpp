// voxlab: drawing the texture slicers' proxy polygons.
#include "voxlab/renderers.h"
#include "voxlab/shader.h"

namespace voxlab {

void drawSlicePolygons(DrawContext& ctx, const std::vector<std::vector<glm::dvec3>>& polygons, bool outline) {
    // Convex polygons become triangle fans; one draw call keeps their order,
    // so blending composites them in the order given.
    std::vector<glm::vec3> triangles, edges;
    for (const auto& polygon : polygons) {
        for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
            for (std::size_t j : {std::size_t(0), i, i + 1}) triangles.push_back(glm::vec3(polygon[j]));
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
