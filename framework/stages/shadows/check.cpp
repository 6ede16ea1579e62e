// voxlab stage shadows: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// light_transmittance_random (stage shadows)

json runLightTransmittance(const std::string& root) {
    CheckRandom rng(0x5EED0013u);
    json check = checkJson("light_transmittance_random", "shadows", rng.seed());
    // Values 0..100 in a 7x6x8 volume of unequal spacings (the smallest 0.6,
    // so the opacity correction's unit length is not 1).
    probe::ProbeVolume volume = randomVolume(rng, glm::ivec3(7, 6, 8), glm::dvec3(0.9, 0.6, 0.75), 100.0, 0.0);
    volume.linearFilter = true;
    const double minSpacing = 0.6;
    GlslProbe probe(root, "stages/shadows/light_transmittance_probe.frag", kMarchConstants);
    probe.setVolume(volume);
    check["fixture"] = {{"volume", volumeJson(volume)}, {"interpolation", "hardware"}, {"min_spacing", minSpacing}};
    constexpr int kFunctions = 4;
    bool notImplemented = false;
    for (int f = 0; f < kFunctions; ++f) {
        ProbeTransferFunction tf = randomTransferFunction(rng);
        // Faint opacities, so that light gets through several voxels.
        for (glm::vec4& e : tf.table) e.a *= f == 0 ? 1.0f : 0.25f;
        for (auto& point : tf.points) point.second.a *= f == 0 ? 1.0f : 0.25f;
        probe.setTransferFunction(tf.table, glm::vec2(0.0f, 100.0f));
        std::vector<glm::vec4> points, directions;
        for (int i = 0; i < kCases / kFunctions; ++i) {
            // Kinds: 0 anywhere inside; 1 on a face; 2 along an axis; 3 a
            // step larger than the box (one sample or none).
            const int kind = i % 4;
            glm::dvec3 p = f32(rng.inBox(glm::dvec3(0.0), glm::dvec3(volume.extent)));
            glm::dvec3 d = rng.unitVector();
            if (kind == 1) {
                const int axis = rng.index(3);
                p[axis] = rng.index(2) ? double(volume.extent[axis]) : 0.0;
            }
            if (kind == 2) {
                d = glm::dvec3(0.0);
                d[rng.index(3)] = rng.index(2) ? 1.0 : -1.0;
            }
            const double step = kind == 3 ? f32(rng.range(4.0, 8.0)) : f32(rng.range(0.1, 0.8));
            points.push_back(glm::vec4(glm::vec3(p), float(step)));
            directions.push_back(glm::vec4(glm::vec3(f32(d)), 0.0f));
        }
        const probe::ProbeResults results = probe.run(int(points.size()), {points, directions});
        notImplemented = notImplemented || results.notImplemented;
        const json tfJson = transferFunctionJson(tf);
        for (std::size_t k = 0; k < points.size(); ++k)
            addCase(check, "light_transmittance",
                    {{"p", vecJson(glm::dvec3(glm::vec3(points[k])))},
                     {"to_light", vecJson(glm::dvec3(glm::vec3(directions[k])))},
                     {"step", double(points[k].w)}, {"transfer_function", tfJson},
                     {"units", "p and step in world units; opacities per unit length (the smallest spacing)"}},
                    number(results.first[k].x));
    }
    check["not_implemented"] = notImplemented;
    return check;
}

CaseVerdict compareLightTransmittance(const std::string&, const json&, const json& e, const json& a) {
    // A product of up to ~150 factors, each rounded in float: 150 x 6e-8
    // ~ 1e-5 relative. 1e-4 also leaves room for stopping once T < 1e-3 (a
    // change below 1e-3 x 0.1 in the next factor... bounded by 1e-3 itself,
    // so stopping early is allowed by the absolute part). A shadow ray that
    // starts at p, runs away from the light or skips the correction is off
    // by far more on most cases.
    return compareNumbers(e, a, 1.1e-3, 1e-4);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(shadows) {
    using namespace voxlab::check;
    checks.add("light_transmittance_random",
               "light_transmittance() through a random 7x6x8 volume with unequal spacings (the smallest 0.6), 4 random "
               "transfer functions: random points inside and on faces, random and axis directions, steps from 0.1 to "
               "8 world units; within 1.1e-3 (stopping once T < 1e-3 is allowed)",
               runLightTransmittance, compareLightTransmittance);
}
