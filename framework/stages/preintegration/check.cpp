// voxlab stage preintegration: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

json runPreintegrateSegment(const std::string& root) {
    CheckRandom rng(0x5EED0012u);
    json check = checkJson("preintegrate_segment_random", "preintegration", rng.seed());
    GlslProbe probe(root, "stages/preintegration/preintegration_probe.frag");
    constexpr int kFunctions = 4;
    bool notImplemented = false;
    for (int f = 0; f < kFunctions; ++f) {
        const ProbeTransferFunction tf = randomTransferFunction(rng);
        probe.setTransferFunction(tf.table, glm::vec2(0.0f, 100.0f));
        std::vector<glm::vec4> cases;
        for (int i = 0; i < kCases / kFunctions; ++i) {
            // Kinds: 0 anywhere; 1 one sub-segment; 2 a constant value; 3
            // values beyond the function's range (clamped by
            // transfer_function); 4 a long segment across the whole range.
            const int kind = i % 5;
            double front = f32(rng.range(0.0, 100.0)), back = f32(rng.range(0.0, 100.0));
            if (kind == 2) back = front;
            if (kind == 3) front = f32(rng.range(-30.0, 0.0)), back = f32(rng.range(100.0, 130.0));
            if (kind == 4) front = 0.0, back = 100.0;
            if (rng.index(2) && kind >= 3) std::swap(front, back);
            const int substeps = kind == 1 ? 1 : 1 + rng.index(kind == 4 ? 200 : 40);
            cases.push_back(glm::vec4(float(front), float(back), float(f32(rng.range(0.05, 6.0))), float(substeps)));
        }
        const probe::ProbeResults results = probe.run(int(cases.size()), {cases});
        notImplemented = notImplemented || results.notImplemented;
        const json points = transferFunctionJson(tf);
        for (std::size_t k = 0; k < cases.size(); ++k) {
            const glm::vec4& c = cases[k];
            const glm::vec4& r = results.first[k];
            addCase(check, "preintegrate_segment",
                    {{"front", double(c.x)}, {"back", double(c.y)}, {"length", double(c.z)},
                     {"substeps", int(c.w)}, {"transfer_function", points},
                     {"units", "length in unit lengths (the smallest spacing); opacities per unit length"}},
                    numbers({r.r, r.g, r.b, r.a}));
        }
    }
    check["not_implemented"] = notImplemented;
    return check;
}

CaseVerdict comparePreintegrateSegment(const std::string&, const json&, const json& e, const json& a) {
    // Up to 200 sub-segments composited in float, each adding a rounding of
    // about 6e-8 to C and A: 200 x 6e-8 ~ 1.2e-5, so 1e-4 leaves room for a
    // different but equivalent order of operations. Skipping the opacity
    // correction, the premultiplication or the middle of the sub-segments
    // is off by 1e-2 or more on most cases.
    return compareNumbers(e, a, 1e-4, 1e-4);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(preintegration) {
    using namespace voxlab::check;
    checks.add("preintegrate_segment_random",
               "preintegrate_segment() for 4 random piecewise-linear transfer functions: random front and back values, "
               "lengths from 0.05 to 6 unit lengths and 1 to 200 sub-segments; one sub-segment, constant values, "
               "values beyond the function's range, segments across the whole range",
               runPreintegrateSegment, comparePreintegrateSegment);
}
