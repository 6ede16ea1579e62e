// voxlab renderer "mip": maximum intensity projection.
#include "voxlab/renderers.h"

namespace voxlab {

std::string MipRenderer::id() const { return "mip"; }

std::string MipRenderer::description() const {
    return "maximum intensity projection: the largest sample along each ray";
}

}  // namespace voxlab
