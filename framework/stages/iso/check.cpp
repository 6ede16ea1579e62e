// voxlab stage iso: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// iso_hit_random_rays (stage iso)

constexpr double kIsovalue = 0.5;

// A ball-shaped field: 1 at `centre`, falling by 1/2 per `radius` away
// from it, plus noise of +-0.02 per voxel, so its isovalue-0.5 surface is a
// slightly bumpy sphere of about that radius (values higher inside).
probe::ProbeVolume ballVolume(CheckRandom& rng, glm::ivec3 dims, glm::dvec3 spacing, glm::dvec3 centre,
                              double radius) {
    probe::ProbeVolume volume;
    volume.dims = dims;
    volume.extent = glm::vec3(glm::dvec3(dims) * spacing);
    volume.linearFilter = true;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const glm::dvec3 p = (glm::dvec3(x, y, z) + 0.5) * spacing;
                const double noise = rng.range(-0.02, 0.02);
                volume.values.push_back(float(1.0 - 0.5 * glm::length(p - centre) / radius + noise));
            }
    return volume;
}

// Whether every sample up to the crossing, and every midpoint the
// bisection evaluates (in exact arithmetic), keeps clear of the isovalue.
bool clearIsoHit(const probe::ProbeVolume& volume, const ProbeRay& ray, double step, int refinements) {
    const int n = clearSampleCount(ray, step);
    if (n < 0) return false;
    auto g = [&](double t) { return probeField(volume, ray.origin + t * ray.direction) - kIsovalue; };
    for (int m = 0; m < n; ++m) {
        const double now = g(sampleT(ray, step, m));
        if (std::abs(now) < kValueMargin) return false;
        if (now < 0.0) continue;
        if (m == 0) return true;  // starts inside: no bisection
        double lo = sampleT(ray, step, m - 1), hi = sampleT(ray, step, m);
        for (int k = 0; k < refinements; ++k) {
            const double mid = 0.5 * (lo + hi), v = g(mid);
            if (std::abs(v) < 0.1 * kValueMargin) return false;
            (v < 0.0 ? lo : hi) = mid;
        }
        return true;
    }
    return true;
}

json runIsoHit(const std::string& root) {
    CheckRandom rng(0x5EED0009u);
    const glm::ivec3 dims(12, 10, 11);
    const glm::dvec3 spacing(0.9, 1.1, 1.0), extent = glm::dvec3(dims) * spacing;
    const glm::dvec3 centre = f32(0.5 * extent + rng.inBox(glm::dvec3(-1.0), glm::dvec3(1.0)));
    const double radius = f32(rng.range(3.0, 3.5));
    const probe::ProbeVolume volume = ballVolume(rng, dims, spacing, centre, radius);
    std::vector<ProbeRay> rays;
    std::vector<double> steps;
    std::vector<int> refinements;
    while (int(rays.size()) < kCases) {
        // Kinds: 0 from outside the box through any point of it (some
        // miss the ball); 1, 2 from outside through the ball; 3 from a
        // point near the centre, inside the ball (the first sample is a hit).
        // Refinements: none for kind 0 (the first sample past the crossing),
        // 4 to 6 otherwise.
        const int kind = int(rays.size() % 4);
        const glm::dvec3 through = kind == 0 ? rng.inBox(0.05 * extent, 0.95 * extent)
                                             : centre + 0.8 * radius * rng.unitVector();
        const double back = kind == 3 ? rng.range(0.0, 0.3) * radius : glm::length(extent) + rng.range(0.1, 2.0);
        const ProbeRay ray = boxRay(rng, extent, kind == 3 ? centre + 0.2 * (through - centre) : through, back);
        const double step = f32(rng.range(0.3, 0.8));
        const int k = kind == 0 ? 0 : 4 + rng.index(3);
        if (!clearIsoHit(volume, ray, step, k)) continue;
        rays.push_back(ray);
        steps.push_back(step);
        refinements.push_back(k);
    }
    const probe::ProbeResults results =
        marchRays(root, "stages/iso/iso_hit_probe.frag", volume, rays, [&](const ShaderProgram& program, int i) {
            program.set("u_step", float(steps[std::size_t(i)]));
            program.set("u_isovalue", float(kIsovalue));
            program.set("u_refinement_steps", refinements[std::size_t(i)]);
        });
    json check = checkJson("iso_hit_random_rays", "iso", rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}, {"interpolation", "hardware"}};
    for (std::size_t k = 0; k < rays.size(); ++k) {
        json input = rayInput(rays[k], steps[k]);
        input["isovalue"] = kIsovalue;
        input["refinement_steps"] = refinements[k];
        const glm::vec4 r = results.first[k];
        addCase(check, "iso_hit", input, {{"hit", probeFlag(r.x)}, {"t", number(r.y)}});
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

CaseVerdict compareIsoHit(const std::string&, const json& input, const json& e, const json& a) {
    bool bothHit = false;
    CaseVerdict flags = compareHitFlags(e, a, &bothHit);
    if (!bothHit) return flags;
    // After k bisection steps the answer is the middle of an interval of
    // step / 2^k around the crossing. With one step fewer it is the middle
    // of the interval twice as long that holds it: exactly step / 2^(k+1)
    // away; with one more, step / 2^(k+2) away; with none (t_m), at least
    // step / 2^(k+1). The tolerance step / 2^(k+3) is a quarter of the
    // first and half of the second, and at k = 6 and the smallest step
    // (0.3) it is 6e-4, 15 times the float rounding of t (t < 40: 4e-5).
    // Without refinement (k = 0) it is step / 8: t_m, not t_(m-1) or the
    // middle between them.
    const double step = input.at("step").get<double>();
    const int k = input.at("refinement_steps").get<int>();
    const CaseVerdict t = compareNumbers(e["t"], a.value("t", json()), std::ldexp(step, -(k + 3)), 0.0);
    if (!t.pass) return {false, t.delta, t.note.empty() ? "t" : "t: " + t.note};
    return t;
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(iso) {
    using namespace voxlab::check;
    checks.add("iso_hit_random_rays",
               "iso_hit() on random rays through a bumpy ball, with random steps and 0 or 4 to 6 bisection steps: "
               "misses, hits from outside, rays starting inside; t within step / 2^(k+3) for k steps",
               runIsoHit, compareIsoHit);
}
