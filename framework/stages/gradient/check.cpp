// voxlab stage gradient: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// gradient_random_points (stage gradient)

json runGradient(const std::string& root) {
    CheckRandom rng(0x5EED0003u);
    const glm::ivec3 dims(6, 7, 5);
    probe::ProbeVolume volume = randomVolume(rng, dims, glm::dvec3(1.2, 0.7, 1.0), 3.0, 1.0);
    // The samples come from the GPU's own trilinear filtering (the program
    // is built with u_interpolation = 2), not from the submission's
    // sampling stage, so that this check sees the gradient stage alone.
    volume.linearFilter = true;
    const glm::dvec3 extent(volume.extent), spacing = extent / glm::dvec3(dims);
    std::vector<glm::vec4> points;
    for (int i = 0; i < kCases; ++i) {
        glm::dvec3 p = rng.inBox(glm::dvec3(0.0), extent);
        const int axis = rng.index(3);
        switch (i % 4) {
        case 1: {  // within one and a half voxels of a face: the clamped, one-sided differences
            const double inset = rng.range(0.0, 1.5) * spacing[axis];
            p[axis] = rng.index(2) ? extent[axis] - inset : inset;
            break;
        }
        case 2:  // on a face
            p[axis] = rng.index(2) ? extent[axis] : 0.0;
            break;
        case 3:  // on a voxel centre
            p = glm::dvec3{double(rng.index(dims.x)), double(rng.index(dims.y)), double(rng.index(dims.z))};
            p = (p + 0.5) * spacing;
            break;
        default:  // anywhere in the box
            break;
        }
        points.push_back(texel(f32(p)));
    }
    GlslProbe probe(root, "stages/gradient/gradient_probe.frag", {{"u_interpolation", 2}});
    probe.setVolume(volume);
    const probe::ProbeResults results = probe.run(kCases, {points});
    json check = checkJson("gradient_random_points", "gradient", rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}, {"interpolation", "hardware"},
                        {"min_spacing", double(std::min({float(spacing.x), float(spacing.y), float(spacing.z)}))}};
    for (int f = 0; f < 2; ++f)
        for (int i = 0; i < kCases; ++i) {
            const glm::vec4 r = (f == 0 ? results.first : results.second)[std::size_t(i)];
            addCase(check, f == 0 ? "gradient_central" : "gradient_sobel",
                    {{"point", vecJson(glm::dvec3(glm::vec3(points[std::size_t(i)])))}}, numbers({r.x, r.y, r.z}));
        }
    check["not_implemented"] = results.notImplemented;
    return check;
}

CaseVerdict compareGradient(const std::string&, const json&, const json& e, const json& a) {
    // Gradients of order 1 to 10 per unit length; value differences in
    // float divided by distances of 0.35 to 2.4: 2e-4 + 1e-4 |e|.
    return compareNumbers(e, a, 2e-4, 1e-4);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(gradient) {
    using namespace voxlab::check;
    checks.add("gradient_random_points",
               "gradient_central() and gradient_sobel() at random points of a random 6x7x5 volume with unequal "
               "spacings, near and on the faces included",
               runGradient, compareGradient);
}
