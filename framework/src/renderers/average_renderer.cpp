// voxlab renderer "average": average intensity projection (X-ray-like).
#include "voxlab/renderers.h"

namespace voxlab {

std::string AverageRenderer::id() const { return "average"; }

std::string AverageRenderer::description() const {
    return "average intensity projection: the mean sample along each ray, like an X-ray";
}

}  // namespace voxlab
