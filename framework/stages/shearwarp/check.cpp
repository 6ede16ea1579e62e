// voxlab stage shearwarp: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"
#include "voxlab/stage_library.h"

namespace voxlab::check {
namespace {

// shear_warp_random (stage shearwarp, C++): factorShearWarp for random
// orthographic cameras (any direction, zoom, pan and image size) over random
// grids with unequal spacings; axis views and 45-degree ties included.

json runShearWarp(const std::string&) {
    CheckRandom rng(0x5EED0016u);
    json check = checkJson("shear_warp_random", "shearwarp", rng.seed());
    for (int i = 0; i < kCases; ++i) {
        const glm::ivec3 dims(4 + rng.index(60), 4 + rng.index(60), 4 + rng.index(60));
        const glm::dvec3 spacing(f32(rng.range(0.5, 3.0)), f32(rng.range(0.5, 3.0)), f32(rng.range(0.5, 3.0)));
        CameraSpec spec;
        spec.projection = Projection::Orthographic;
        if (i % 8 == 1) {
            spec.view = std::string(rng.index(2) ? "+" : "-") + "xyz"[rng.index(3)];
        } else {
            spec.azimuth = i % 8 == 2 ? 45.0 : f32(rng.range(-180.0, 180.0));  // 45: a tie in voxel units only if the spacings agree
            spec.elevation = f32(rng.range(-85.0, 85.0));
        }
        spec.zoom = f32(rng.range(0.5, 3.0));
        spec.pan = glm::dvec2(f32(rng.range(-0.3, 0.3)), f32(rng.range(-0.3, 0.3)));
        const Camera cam = Camera::make(spec, glm::dvec3(dims) * spacing, 32 + rng.index(400), 32 + rng.index(400));
        const json input = {{"dims", {dims.x, dims.y, dims.z}},
                            {"spacing", vecJson(spacing)},
                            {"camera", {{"position", vecJson(cam.position)}, {"forward", vecJson(cam.forward)},
                                        {"right", vecJson(cam.right)}, {"down", vecJson(cam.down)},
                                        {"pixel_scale", cam.pixelScale}, {"width", cam.width}, {"height", cam.height}}}};
        addCase(check, "factorShearWarp", input, callStage([&] {
                    const ShearWarp sw = cppStages().factorShearWarp(cam, dims, spacing);
                    json warp = json::array();
                    for (int col = 0; col < 3; ++col)
                        for (int row = 0; row < 3; ++row) warp.push_back(sw.warp[col][row]);
                    return json{{"axis", sw.axis}, {"front", sw.front}, {"shear", {sw.shear.x, sw.shear.y}},
                                {"offset", {sw.offset.x, sw.offset.y}}, {"size", {sw.size.x, sw.size.y}},
                                {"warp", warp}};
                }));
    }
    check["not_implemented"] = false;
    return check;
}

CaseVerdict compareShearWarp(const std::string&, const json&, const json& e, const json& a) {
    if (!a.is_object() || !a.contains("axis")) return failure("no result");
    for (const char* whole : {"axis", "front", "size"})
        if (a[whole] != e[whole]) return failure(std::string(whole) + " is wrong");
    // Shears of at most 1, offsets and warps of order 100 from a few
    // products and one division in double: 1e-9 (1 + |x|).
    for (const char* part : {"shear", "offset", "warp"}) {
        const CaseVerdict v = compareNumbers(e[part], a[part], 1e-9, 1e-9);
        if (!v.pass) return v;
    }
    return {};
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(shearwarp) {
    using namespace voxlab::check;
    checks.add("shear_warp_random",
               "factorShearWarp() for random orthographic cameras (any direction, zoom, pan, image size; axis views) "
               "over random grids with unequal spacings; axis, front slice and size exactly, shear, offset and warp "
               "within 1e-9 (1 + |x|)",
               runShearWarp, compareShearWarp);
}
