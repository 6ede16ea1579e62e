// voxlab stage firsthit: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// first_hit_random_rays (stage firsthit)

// Whether every sample up to the first hit keeps clear of the threshold.
bool clearFirstHit(const probe::ProbeVolume& volume, const ProbeRay& ray, double step, double threshold) {
    const int n = clearSampleCount(ray, step);
    if (n < 0) return false;
    for (int m = 0; m < n; ++m) {
        const double v = probeField(volume, ray.origin + sampleT(ray, step, m) * ray.direction);
        if (std::abs(v - threshold) < kValueMargin) return false;
        if (v >= threshold) return true;
    }
    return true;
}

json runFirstHit(const std::string& root) {
    CheckRandom rng(0x5EED0008u);
    probe::ProbeVolume volume = randomVolume(rng, glm::ivec3(7, 6, 8), glm::dvec3(1.0, 0.8, 1.2), 2.0, -0.5);
    volume.linearFilter = true;
    const glm::dvec3 extent(volume.extent);
    std::vector<ProbeRay> rays;
    std::vector<double> steps, thresholds;
    while (int(rays.size()) < kCases) {
        // Steps of 0.15 to 0.7 units (the smallest spacing is 0.8);
        // thresholds that some rays reach.
        const ProbeRay ray = marchingRay(rng, extent, rays.size());
        const double step = f32(rng.range(0.15, 0.7));
        const double threshold = f32(rng.range(0.7, 1.3));
        if (!clearFirstHit(volume, ray, step, threshold)) continue;
        rays.push_back(ray);
        steps.push_back(step);
        thresholds.push_back(threshold);
    }
    const probe::ProbeResults results =
        marchRays(root, "stages/firsthit/first_hit_probe.frag", volume, rays, [&](const ShaderProgram& program, int i) {
            program.set("u_step", float(steps[std::size_t(i)]));
            program.set("u_threshold", float(thresholds[std::size_t(i)]));
        });
    json check = checkJson("first_hit_random_rays", "firsthit", rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}, {"interpolation", "hardware"}};
    for (std::size_t k = 0; k < rays.size(); ++k) {
        json input = rayInput(rays[k], steps[k]);
        input["threshold"] = thresholds[k];
        const glm::vec4 r = results.first[k];
        addCase(check, "first_hit", input, {{"hit", probeFlag(r.x)}, {"t", number(r.y)}, {"value", number(r.z)}});
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

CaseVerdict compareFirstHit(const std::string&, const json&, const json& e, const json& a) {
    bool bothHit = false;
    CaseVerdict flags = compareHitFlags(e, a, &bothHit);
    if (!bothHit) return flags;
    // The same samples give the same hit, so t differs only by rounding:
    // t_entry + (m + 1/2) step in float is within a few 1e-6 of t, and
    // summing t += step over up to 200 samples (t < 40) within 4e-4. The
    // tolerance 1e-4 (1 + |t|) allows that and stays at most 4e-3 (t < 40),
    // 20 times below half the smallest step (0.15 / 2): a hit half a step
    // off (no + 1/2), a step off or a sample off fails. The value is read
    // at the same position, to ~1e-5; values span 2: 1e-4 (1 + |value|).
    const CaseVerdict t = compareNumbers(e["t"], a.value("t", json()), 1e-4, 1e-4);
    if (!t.pass) return {false, t.delta, t.note.empty() ? "t" : "t: " + t.note};
    const CaseVerdict value = compareNumbers(e["value"], a.value("value", json()), 1e-4, 1e-4);
    if (!value.pass) return {false, value.delta, value.note.empty() ? "value" : "value: " + value.note};
    return t;
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(firsthit) {
    using namespace voxlab::check;
    checks.add("first_hit_random_rays",
               "first_hit() on random rays through a random 7x6x8 volume, with random steps and thresholds: rays from "
               "outside the box and from inside it, hits and misses; t within 1e-4 (1 + |t|), far below half a step",
               runFirstHit, compareFirstHit);
}
