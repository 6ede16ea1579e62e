// voxlab stage texslice2d: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"
#include "voxlab/stage_library.h"

namespace voxlab::check {
namespace {

// slice_axis_random (stage texslice2d)

json runSliceAxis(const std::string& root) {
    CheckRandom rng(0x5EED0006u);
    json check = checkJson("slice_axis_random", "texslice2d", rng.seed());

    // chooseSliceAxis (C++). Exact ties are built from one number with its
    // sign flipped, so they are ties in any arithmetic.
    for (int i = 0; i < kCases; ++i) {
        glm::dvec3 d;
        const double a = f32(rng.range(0.3, 1.0)), b = f32(a * rng.range(0.0, 0.95));
        auto sign = [&]() { return rng.index(2) ? 1.0 : -1.0; };
        switch (i % 5) {
        case 0:  // any direction, of any length
            d = f32(rng.unitVector() * std::ldexp(1.0, rng.index(21) - 10));
            break;
        case 1:  // the two largest components tie
            d = glm::dvec3{sign() * a, sign() * a, sign() * b};
            break;
        case 2:  // all three tie
            d = glm::dvec3{sign() * a, sign() * a, sign() * a};
            break;
        case 3:  // the two smaller components tie
            d = glm::dvec3{sign() * a, sign() * b, sign() * b};
            break;
        default:  // along an axis, or (once) no direction at all
            d = glm::dvec3(0.0);
            if (i != 4) d[rng.index(3)] = sign() * a;
        }
        if (i % 5 >= 1 && i % 5 <= 3) {  // a random order of the components
            const int shift = rng.index(3);
            d = glm::dvec3(d[shift], d[(shift + 1) % 3], d[(shift + 2) % 3]);
            if (rng.index(2)) std::swap(d.x, d.y);
        }
        const json output = callStage([&] { return json(cppStages().chooseSliceAxis(d)); });
        addCase(check, "chooseSliceAxis", {{"view_direction", vecJson(d)}}, output);
    }

    // slice_opacity (GLSL): the stack's axis, the slice spacing and the
    // unit length are uniforms, set per case.
    struct Setting {
        int axis;
        double sliceSpacing, minSpacing;
    };
    std::vector<Setting> settings;
    std::vector<glm::vec4> inputs;
    for (int i = 0; i < kCases; ++i) {
        Setting s{rng.index(3), f32(rng.range(0.3, 2.0)), f32(rng.range(0.3, 2.0))};
        glm::dvec3 direction;
        do direction = unitF32(rng.unitVector());
        while (std::abs(direction[s.axis]) < 0.3);  // drawn stacks face the viewer at least this much
        const double alpha = i % 10 == 0 ? 0.0 : i % 10 == 1 ? 1.0 : f32(rng.uniform());
        settings.push_back(s);
        inputs.push_back(texel(direction, alpha));
    }
    GlslProbe probe(root, "stages/texslice2d/slice_opacity_probe.frag");
    const probe::ProbeResults results = probe.run(kCases, {inputs}, [&](const ShaderProgram& program, int i) {
        const Setting& s = settings[std::size_t(i)];
        program.set("u_stack_axis", s.axis);
        program.set("u_slice_spacing", float(s.sliceSpacing));
        program.set("u_min_spacing", float(s.minSpacing));
    });
    for (int i = 0; i < kCases; ++i) {
        const std::size_t k = std::size_t(i);
        addCase(check, "slice_opacity",
                {{"alpha", double(inputs[k].w)},
                 {"direction", vecJson(glm::vec3(inputs[k]))},
                 {"stack_axis", settings[k].axis},
                 {"slice_spacing", settings[k].sliceSpacing},
                 {"min_spacing", settings[k].minSpacing}},
                number(results.first[k].x));
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

CaseVerdict compareSliceAxis(const std::string& function, const json&, const json& e, const json& a) {
    if (function == "chooseSliceAxis") return compareExact(e, a);  // an axis index, ties included
    // An opacity in [0, 1] from one pow(): 1e-4.
    return compareNumbers(e, a, 1e-4, 0.0);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(texslice2d) {
    using namespace voxlab::check;
    checks.add("slice_axis_random",
               "chooseSliceAxis() on random directions with exact ties, and slice_opacity() on random slices",
               runSliceAxis, compareSliceAxis);
}
