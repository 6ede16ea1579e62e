// voxlab stage mida: maximum intensity difference accumulation (Bruckner and
// Groeller 2009), a ray-colour stage (vec4 mida_ray() in
// reference/mida/mida.glsl; its gamma becomes the uniform u_gamma).
#include "voxlab/renderers.h"

VOXLAB_RENDERERS(mida) {
    registry.add<voxlab::RayValueRenderer>(
        "mida",
        "maximum intensity difference accumulation: compositing where a new maximum pushes back what lies in front, "
        "between compositing (gamma -1) and MIP (gamma 1)",
        voxlab::ProfileModel::None,
        std::vector<voxlab::ParameterSpec>{{"gamma", voxlab::ParameterType::Float, -1.0, 1.0, 0.0,
                                            "-1: compositing, 0: MIDA, 1: MIP"}},
        voxlab::RayResult::Colour);
}
