// voxlab stage splat: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"
#include "voxlab/stage_library.h"

namespace voxlab::check {
namespace {

// splat_order_random (stage splat, C++): splatOrder on random directions,
// ties of two and three components (built from one number, so exact in
// any arithmetic), zero components, any length.

json runSplatOrder(const std::string&) {
    CheckRandom rng(0x5EED0015u);
    json check = checkJson("splat_order_random", "splat", rng.seed());
    for (int i = 0; i < kCases; ++i) {
        const double a = f32(rng.range(0.3, 1.0)), b = f32(a * rng.range(0.05, 0.95));
        auto sign = [&]() { return rng.index(2) ? 1.0 : -1.0; };
        glm::dvec3 d;
        switch (i % 5) {
        case 0: d = f32(rng.unitVector() * std::ldexp(1.0, rng.index(21) - 10)); break;
        case 1: d = {sign() * a, sign() * a, sign() * b}; break;  // the two largest tie
        case 2: d = {sign() * a, sign() * b, sign() * b}; break;  // the two smallest tie
        case 3: d = {sign() * a, sign() * a, sign() * a}; break;  // all three tie
        default: d = {sign() * a, sign() * b, 0.0};               // one component zero
        }
        const int shift = rng.index(3);  // a random order of the components
        d = glm::dvec3(d[shift], d[(shift + 1) % 3], d[(shift + 2) % 3]);
        if (rng.index(2)) std::swap(d.x, d.y);
        addCase(check, "splatOrder", {{"view_direction", vecJson(d)}}, callStage([&] {
                    const SplatOrder o = cppStages().splatOrder(d);
                    return json{{"axes", o.axes}, {"step", o.step}};
                }));
    }
    check["not_implemented"] = false;
    return check;
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(splat) {
    using namespace voxlab::check;
    checks.add("splat_order_random",
               "splatOrder() on random view directions of any length, with two or three components tied exactly "
               "and with a zero component; axes and steps compared exactly",
               runSplatOrder, [](const std::string&, const json&, const json& e, const json& a) { return compareExact(e, a); });
}
