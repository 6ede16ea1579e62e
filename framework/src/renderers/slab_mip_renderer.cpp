// voxlab renderer "slab_mip": thin-slab maximum intensity projection.
#include "voxlab/renderers.h"

#include "voxlab/camera.h"
#include "voxlab/volume.h"

namespace voxlab {

std::string SlabMipRenderer::id() const { return "slab_mip"; }

std::string SlabMipRenderer::description() const {
    return "thin-slab MIP: MIP of a slab perpendicular to the view, moved by 'offset'";
}

std::vector<ParameterSpec> SlabMipRenderer::parameters() const {
    return {{"offset", ParameterType::Float, -4096.0, 4096.0, 0.0,
             "distance of the slab's centre plane from the volume centre along the view direction, "
             "in units of the smallest voxel spacing"},
            {"thickness", ParameterType::Float, 0.0, 8192.0, 16.0,
             "thickness of the slab, in units of the smallest voxel spacing"}};
}

// The slab: |dot(p - c, forward)| <= thickness/2 around the box centre moved
// by `offset` along the view (both in smallest spacings), as slab_mip.frag
// asks clip_to_slab() to do.
bool SlabMipRenderer::clipProfileRay(const Volume& volume, const glm::dvec3& forward, const ParameterValues& values,
                                     const glm::dvec3& origin, const glm::dvec3& dir, double* t0, double* t1) const {
    const glm::dvec3 centre = 0.5 * volume.extent() + values.at("offset") * volume.minSpacing() * forward;
    const double h = 0.5 * values.at("thickness") * volume.minSpacing();
    return clipToHalfSpace(origin, dir, centre - h * forward, forward, t0, t1) &&
           clipToHalfSpace(origin, dir, centre + h * forward, -forward, t0, t1);
}

}  // namespace voxlab
