// voxlab stage gradient_opacity: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// gradient_opacity_random (stage gradient_opacity): the ramp's weight for
// random magnitudes and bounds of every size (8-bit to 16-bit data, per unit
// length), with magnitudes below, inside and above the ramp, exactly on its
// bounds, and equal or reversed bounds (a step at high).
json runGradientOpacity(const std::string& root) {
    CheckRandom rng(0x5EED0010u);
    json check = checkJson("gradient_opacity_random", "gradient_opacity", rng.seed());
    std::vector<glm::vec4> cases;
    for (int i = 0; i < kCases; ++i) {
        const double scale = std::pow(10.0, rng.range(-1.0, 4.0));  // bounds from 0.1 to 10^4
        double low = f32(scale * rng.range(0.0, 0.5)), high = f32(low + scale * rng.range(0.05, 1.0));
        const int kind = i % 8;
        if (kind == 6) high = low;                                  // a step
        if (kind == 7) std::swap(low, high);                        // reversed: a step at high
        double g = f32(rng.range(0.0, 1.5) * std::max(low, high) + rng.range(0.0, 0.1) * scale);
        if (kind == 3) g = low;                                     // exactly on the bounds
        if (kind == 4 || kind == 6) g = high;
        if (kind == 5) g = f32(0.5 * low);                          // well below
        cases.push_back(glm::vec4(float(g), float(low), float(high), 0.0f));
    }
    GlslProbe probe(root, "stages/gradient_opacity/gradient_opacity_probe.frag");
    const probe::ProbeResults results = probe.run(kCases, {cases});
    for (int i = 0; i < kCases; ++i) {
        const glm::vec4& c = cases[std::size_t(i)];
        addCase(check, "gradient_opacity_weight",
                {{"gradient_magnitude", double(c.x)}, {"low", double(c.y)}, {"high", double(c.z)},
                 {"units", "data units per unit length (the smallest spacing)"}},
                number(results.first[std::size_t(i)].x));
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

CaseVerdict compareGradientOpacity(const std::string&, const json&, const json& e, const json& a) {
    // A weight in [0, 1] from one subtraction and one division in float:
    // 1e-5. An unclamped, reversed or curved ramp is off by far more, and a
    // step on the wrong side by 1.
    return compareNumbers(e, a, 1e-5, 0.0);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(gradient_opacity) {
    using namespace voxlab::check;
    checks.add("gradient_opacity_random",
               "gradient_opacity_weight() for random gradient magnitudes and bounds from 0.1 to 10^4 data units per "
               "unit length: below, inside and above the ramp, exactly on its bounds, equal and reversed bounds",
               runGradientOpacity, compareGradientOpacity);
}
