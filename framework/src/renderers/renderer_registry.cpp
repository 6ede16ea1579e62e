// voxlab: the explicit list of built-in renderers, in teaching order. A new
// renderer is added here, in one line; nothing registers itself behind the
// linker's back. A ray-value stage (one value per ray, <stage>_ray()) needs
// no class and no entry shader: RayValueRenderer is its line.
#include "voxlab/renderers.h"

namespace voxlab {

const RendererRegistry& rendererRegistry() {
    static const RendererRegistry registry = [] {
        RendererRegistry r;
        r.add<SlicerRenderer>();
        r.add<MipRenderer>();
        r.add<RayValueRenderer>("minip", "minimum intensity projection: the smallest sample along each ray",
                                ProfileModel::Minimum);
        r.add<RayValueRenderer>("average", "average intensity projection: the mean sample along each ray, like an X-ray",
                                ProfileModel::Mean);
        r.add<FirstHitRenderer>();
        r.add<SlabMipRenderer>();
        r.add<RayValueRenderer>("attenuated_mip",
                                "attenuated MIP: each sample dimmed by the intensity in front of it and, with a "
                                "depth cue, by its depth",
                                ProfileModel::None,
                                std::vector<ParameterSpec>{{"attenuation", ParameterType::Float, 0.0, 10.0, 0.05,
                                                            "dimming per unit length of normalised intensity crossed"},
                                                           {"depth_cue", ParameterType::Float, 0.0, 1.0, 0.0,
                                                            "depth cue: dimming per unit length (smallest spacing) "
                                                            "behind where the ray enters; 0 turns it off"}});
        r.add<CompositeRenderer>();
        r.add<RayValueRenderer>("mida", "maximum intensity difference accumulation: compositing where a new maximum pushes back what lies in front, between compositing (gamma -1) and MIP (gamma 1)", ProfileModel::None, std::vector<ParameterSpec>{{"gamma", ParameterType::Float, -1.0, 1.0, 0.0, "-1: compositing, 0: MIDA, 1: MIP"}}, RayResult::Colour);
        r.add<IsoRenderer>();
        r.add<MeshRenderer>();
        r.add<Tf2dRenderer>();
        r.add<Texslice2dRenderer>();
        r.add<Texslice3dRenderer>();
        r.add<SplatRenderer>();
        r.add<ShearWarpRenderer>();
        return r;
    }();
    return registry;
}

}  // namespace voxlab
