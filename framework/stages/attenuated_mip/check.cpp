// voxlab stage attenuated_mip: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// attenuated_mip_random_rays (stage attenuated_mip): as the projections,
// with a random attenuation (0..0.5 per unit length of normalised
// intensity) and depth cue (0..0.1 per unit length) per ray; a quarter of
// the rays have one of them 0, so each term is also seen alone.
json runAttenuatedMipRays(const std::string& root) {
    CheckRandom rng(0x5EED0011u);
    probe::ProbeVolume volume = randomVolume(rng, glm::ivec3(6, 7, 5), glm::dvec3(1.3, 0.8, 1.1), 65535.0, -32768.0);
    for (float& v : volume.values) v = float(std::round(double(v) * 65535.0) / 65535.0);
    volume.linearFilter = true;
    const double minSpacing = f32(std::min({volume.extent.x / 6.0, volume.extent.y / 7.0, volume.extent.z / 5.0}));
    std::vector<ProbeRay> rays;
    std::vector<double> steps;
    std::vector<glm::dvec3> settings;  // step, attenuation, depth cue
    randomRays(rng, glm::dvec3(volume.extent), &rays, &steps, [&] {
        const int kind = int(settings.size()) % 4;
        settings.push_back({steps.back(), kind == 1 ? 0.0 : f32(rng.range(0.0, 0.5)), kind == 2 ? 0.0 : f32(rng.range(0.0, 0.1))});
    });
    const probe::ProbeResults results =
        marchRays(root, "stages/attenuated_mip/attenuated_mip_probe.frag", volume, rays, [&](const ShaderProgram& program, int i) {
            const glm::dvec3& c = settings[std::size_t(i)];
            program.set("u_step", float(c.x));
            program.set("u_step_units", float(c.x / minSpacing));
            program.set("u_attenuation", float(c.y));
            program.set("u_depth_cue", float(c.z));
        });
    json check = checkJson("attenuated_mip_random_rays", "attenuated_mip", rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}, {"interpolation", "hardware"}, {"min_spacing", minSpacing}};
    for (std::size_t k = 0; k < rays.size(); ++k) {
        json input = rayInput(rays[k], settings[k].x);
        input["step_units"] = f32(settings[k].x / minSpacing);
        input["attenuation"] = settings[k].y;
        input["depth_cue"] = settings[k].z;
        input["units"] = "attenuation per unit length of intensity normalised to the volume's range, depth cue per "
                         "unit length; unit length = the smallest spacing";
        addCase(check, "attenuated_mip_ray", input, {{"value", number(results.first[k].x)}});
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(attenuated_mip) {
    using namespace voxlab::check;
    checks.add("attenuated_mip_random_rays",
               "attenuated_mip_ray() on random rays through a random 6x7x5 volume of int16 values with unequal spacings, "
               "random steps, attenuations and depth cues (each alone on a quarter of the rays); values within 8",
               runAttenuatedMipRays, compareProjection);
}
