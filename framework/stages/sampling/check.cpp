// voxlab stage sampling: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// trilinear_random_points (stage sampling)

json runTrilinear(const std::string& root) {
    CheckRandom rng(0x5EED0002u);
    const glm::ivec3 dims(7, 5, 6);
    const probe::ProbeVolume volume = randomVolume(rng, dims, glm::dvec3(0.8, 1.3, 1.0), 2.0, -0.5);
    const glm::dvec3 extent(volume.extent), spacing = extent / glm::dvec3(dims);
    std::vector<glm::vec4> points;
    for (int i = 0; i < kCases; ++i) {
        glm::dvec3 p;
        switch (i % 4) {
        case 0:  // anywhere in the box
            p = rng.inBox(glm::dvec3(0.0), extent);
            break;
        case 1: {  // near a face, or on it
            p = rng.inBox(glm::dvec3(0.0), extent);
            const int axis = rng.index(3);
            const double inset = rng.index(2) == 0 ? 0.0 : rng.range(0.0, 0.02) * spacing[axis];
            p[axis] = rng.index(2) ? extent[axis] - inset : inset;
            break;
        }
        case 2: {  // on a voxel centre
            const glm::dvec3 voxel{double(rng.index(dims.x)), double(rng.index(dims.y)), double(rng.index(dims.z))};
            p = (voxel + 0.5) * spacing;
            break;
        }
        default: {  // up to half a voxel outside a face: the border value continues
            p = rng.inBox(glm::dvec3(0.0), extent);
            const int axis = rng.index(3);
            const double outside = rng.range(0.001, 0.5) * spacing[axis];
            p[axis] = rng.index(2) ? extent[axis] + outside : -outside;
        }
        }
        // Nearest neighbour jumps at the voxel boundaries inside the grid:
        // keep a thousandth of a voxel away from them.
        for (int a = 0; a < 3; ++a) {
            const double c = p[a] / spacing[a], k = std::round(c);
            if (k >= 1.0 && k <= dims[a] - 1.0 && std::abs(c - k) < 1e-3) p[a] += 2e-3 * spacing[a];
        }
        points.push_back(texel(f32(p)));
    }
    GlslProbe probe(root, "stages/sampling/sampling_probe.frag");
    probe.setVolume(volume);
    const probe::ProbeResults results = probe.run(kCases, {points});
    json check = checkJson("trilinear_random_points", "sampling", rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}};
    for (int f = 0; f < 2; ++f)
        for (int i = 0; i < kCases; ++i) {
            const glm::vec4 r = results.first[std::size_t(i)];
            addCase(check, f == 0 ? "sample_trilinear" : "sample_nearest",
                    {{"point", vecJson(glm::dvec3(glm::vec3(points[std::size_t(i)])))}}, number(f == 0 ? r.x : r.y));
        }
    check["not_implemented"] = results.notImplemented;
    return check;
}

CaseVerdict compareSampling(const std::string& function, const json&, const json& e, const json& a) {
    // Values span [-0.5, 1.5]. Trilinear: weights and mixes in float, about
    // 1e-7 each, so 2e-5. Nearest returns a stored voxel value: 1e-6.
    return compareNumbers(e, a, function == "sample_nearest" ? 1e-6 : 2e-5, 0.0);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(sampling) {
    using namespace voxlab::check;
    checks.add("trilinear_random_points",
               "sample_trilinear() and sample_nearest() at random points of a random 7x5x6 volume with unequal "
               "spacings: inside, near and on the faces, on voxel centres, just outside",
               runTrilinear, compareSampling);
}
