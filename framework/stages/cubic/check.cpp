// voxlab stage cubic: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// cubic_random_points (stage cubic): Catmull-Rom values and gradients at
// random points of a random volume with unequal spacings (inside, near and
// on faces, on voxel centres), and both kernels' weights and derivative
// weights at random fractions (and at 0).

json runCubic(const std::string& root) {
    CheckRandom rng(0x5EED0013u);
    const glm::ivec3 dims(7, 6, 5);
    const probe::ProbeVolume volume = randomVolume(rng, dims, glm::dvec3(0.8, 1.3, 1.0), 2.0, -0.5);
    const glm::dvec3 extent(volume.extent), spacing = extent / glm::dvec3(dims);
    std::vector<glm::vec4> points, fractions;
    for (int i = 0; i < kCases; ++i) {
        glm::dvec3 p = rng.inBox(glm::dvec3(0.0), extent);
        if (i % 4 == 1) {  // on a face
            const int axis = rng.index(3);
            p[axis] = rng.index(2) ? 0.0 : extent[axis];
        }
        if (i % 4 == 2)  // on a voxel centre
            p = (glm::dvec3(rng.index(dims.x), rng.index(dims.y), rng.index(dims.z)) + 0.5) * spacing;
        points.push_back(texel(f32(p)));
        const double t = i % 16 == 3 ? 0.0 : f32(rng.uniform());
        fractions.push_back(glm::vec4(float(t), float(3 + i % 2), float((i / 2) % 2), 0.0f));
    }
    GlslProbe probe(root, "stages/cubic/cubic_probe.frag", {{"u_interpolation", 4}});
    probe.setVolume(volume);
    const probe::ProbeResults results = probe.run(kCases, {points, fractions});
    json check = checkJson("cubic_random_points", "cubic", rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}, {"kernel", "Catmull-Rom (u_interpolation 4)"}};
    for (int i = 0; i < kCases; ++i) {
        const glm::vec4 r = results.first[std::size_t(i)], w = results.second[std::size_t(i)];
        const json point = {{"point", vecJson(glm::dvec3(glm::vec3(points[std::size_t(i)])))}};
        addCase(check, "sample_cubic", point, number(r.x));
        addCase(check, "gradient_cubic", point, numbers({r.y, r.z, r.w}));
        const glm::vec4 f = fractions[std::size_t(i)];
        addCase(check, f.z != 0.0f ? "cubic_derivative_weights" : "cubic_weights",
                {{"t", double(f.x)}, {"kernel", f.y == 3.0f ? "bspline (3)" : "catmull-rom (4)"}},
                numbers({w.x, w.y, w.z, w.w}));
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

CaseVerdict compareCubic(const std::string& function, const json&, const json& e, const json& a) {
    // Weights: cubic polynomials of t in [0, 1) in float, of order 1: 1e-5.
    // Values span [-0.5, 1.5], 64 taps summed in float: 5e-5. Gradients of
    // order 1 to 10 per unit length, 64 products each: 5e-4 + 1e-4 |e|.
    if (function == "gradient_cubic") return compareNumbers(e, a, 5e-4, 1e-4);
    return compareNumbers(e, a, function == "sample_cubic" ? 5e-5 : 1e-5, 0.0);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(cubic) {
    using namespace voxlab::check;
    checks.add("cubic_random_points",
               "Catmull-Rom sample_cubic() and gradient_cubic() at random points of a random 7x6x5 volume with unequal "
               "spacings (near and on faces, on voxel centres), and cubic_weights() and cubic_derivative_weights() of "
               "both kernels at random fractions t",
               runCubic, compareCubic);
}
