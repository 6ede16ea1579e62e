// voxlab stage attenuated_mip: MIP with each sample dimmed by what lies in
// front of it, a ray-value stage (attenuated_mip_ray() in
// reference/attenuated_mip/attenuated_mip.glsl; its parameters become the
// uniforms u_attenuation and u_depth_cue).
#include "voxlab/renderers.h"

VOXLAB_RENDERERS(attenuated_mip) {
    using voxlab::ParameterType;
    registry.add<voxlab::RayValueRenderer>(
        "attenuated_mip",
        "attenuated MIP: each sample dimmed by the intensity in front of it and, with a depth cue, by its depth",
        voxlab::ProfileModel::None,
        std::vector<voxlab::ParameterSpec>{
            {"attenuation", ParameterType::Float, 0.0, 10.0, 0.05,
             "dimming per unit length of normalised intensity crossed"},
            {"depth_cue", ParameterType::Float, 0.0, 1.0, 0.0,
             "depth cue: dimming per unit length (smallest spacing) behind where the ray enters; 0 turns it off"}});
}
