// voxlab stage average: average intensity projection, a ray-value stage
// (average_ray() in reference/average/average.glsl; RayValueRenderer makes
// its entry shader).
#include "voxlab/renderers.h"

VOXLAB_RENDERERS(average) {
    registry.add<voxlab::RayValueRenderer>(
        "average", "average intensity projection: the mean sample along each ray, like an X-ray",
        voxlab::ProfileModel::Mean);
}
