// voxlab renderer "minip": minimum intensity projection.
#include "voxlab/renderers.h"

namespace voxlab {

std::string MinipRenderer::id() const { return "minip"; }

std::string MinipRenderer::description() const {
    return "minimum intensity projection: the smallest sample along each ray";
}

}  // namespace voxlab
