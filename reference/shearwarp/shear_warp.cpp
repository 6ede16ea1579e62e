// Stage: shear-warp, the factorisation (Lacroute and Levoy 1994). The
// contract and the coordinates are in framework/stages/shearwarp/include/voxlab/shear_warp.h.
//
// The view direction, measured in voxels (forward / spacing), decides
// everything: the principal axis c is its largest component, so that rays
// cross every slice perpendicular to c; moving one slice along c, a ray
// moves -v_a / v_c voxels along a and -v_b / v_c along b, which the shear
// undoes. Once sheared, all points of a ray share one intermediate position
// (u, w), and the warp is the camera's projection of the slice x_c = 0,
// written in u and w.
#include "voxlab/error.h"  // NotImplemented, for the student stubs
#include "voxlab/shear_warp.h"

#include <cmath>

namespace voxlab {

ShearWarp factorShearWarp(const Camera& camera, glm::ivec3 dims, glm::dvec3 spacing) {
    if (camera.projection != Projection::Orthographic)
        throw Error("shearwarp: orthographic views only (the perspective factorisation is not implemented)");
    // BEGIN SOLUTION
    ShearWarp sw;
    const glm::dvec3 v = camera.forward / spacing;
    sw.axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(v[k]) > std::abs(v[sw.axis])) sw.axis = k;
    const int c = sw.axis, a = (c + 1) % 3, b = (c + 2) % 3;
    sw.front = v[c] > 0.0 ? 0 : dims[c] - 1;
    sw.shear = {-v[a] / v[c], -v[b] / v[c]};
    sw.offset = {std::max(0.0, -sw.shear.x * dims[c]), std::max(0.0, -sw.shear.y * dims[c])};
    sw.size = {int(std::ceil(dims[a] + std::abs(sw.shear.x) * dims[c])),
               int(std::ceil(dims[b] + std::abs(sw.shear.y) * dims[c]))};
    // pixel = centre + (dot(X - position, right), dot(X - position, down)) / pixelScale,
    // with X = (u - offset_a) spacing_a e_a + (w - offset_b) spacing_b e_b on the slice x_c = 0.
    const glm::dvec3 ea = glm::dvec3(a == 0, a == 1, a == 2) * spacing[a];
    const glm::dvec3 eb = glm::dvec3(b == 0, b == 1, b == 2) * spacing[b];
    const glm::dvec2 du(glm::dot(ea, camera.right), glm::dot(ea, camera.down));
    const glm::dvec2 dw(glm::dot(eb, camera.right), glm::dot(eb, camera.down));
    const glm::dvec2 centre = 0.5 * glm::dvec2(camera.width, camera.height) -
                              glm::dvec2(glm::dot(camera.position, camera.right), glm::dot(camera.position, camera.down)) /
                                  camera.pixelScale;
    const glm::dvec2 origin = centre - (sw.offset.x * du + sw.offset.y * dw) / camera.pixelScale;
    sw.warp = glm::dmat3(glm::dvec3(du / camera.pixelScale, 0.0), glm::dvec3(dw / camera.pixelScale, 0.0),
                         glm::dvec3(origin, 1.0));
    return sw;
    // END SOLUTION
}

}  // namespace voxlab
