// voxlab stage minip: minimum intensity projection, a ray-value stage
// (minip_ray() in reference/minip/minip.glsl; RayValueRenderer makes its
// entry shader).
#include "voxlab/renderers.h"

VOXLAB_RENDERERS(minip) {
    registry.add<voxlab::RayValueRenderer>("minip", "minimum intensity projection: the smallest sample along each ray",
                                           voxlab::ProfileModel::Minimum);
}
