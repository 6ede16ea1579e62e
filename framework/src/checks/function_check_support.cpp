// voxlab: what the stages' function checks share (function_check_support.h).
#include "voxlab/function_check_support.h"

#include "voxlab/error.h"
#include "voxlab/project_root.h"
#include "voxlab/shader.h"

namespace voxlab::check {

double f32(double x) { return double(float(x)); }

// GCC 12's SLP vectorizer compiled this (not inlined) into one that rounds
// z alone, x and y coming back unrounded; this file and the stages'
// check.cpp are therefore built without it (framework/CMakeLists.txt), and
// the test FunctionChecks.FloatRoundingIsKept holds the built code to it.
glm::dvec3 f32(glm::dvec3 v) { return glm::dvec3(glm::vec3(v)); }

glm::dvec3 unitF32(glm::dvec3 v) { return f32(glm::normalize(v)); }

glm::vec4 texel(glm::dvec3 v, double w) { return glm::vec4(glm::vec3(v), float(w)); }

json vecJson(glm::dvec3 v) { return json::array({v.x, v.y, v.z}); }

glm::dvec3 vecOf(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json numbers(std::initializer_list<float> values) {
    json a = json::array();
    for (float v : values) a.push_back(number(v));
    return a;
}

json checkJson(const std::string& name, const std::string& stage, std::uint32_t seed) {
    return {{"check", name}, {"stage", stage}, {"seed", seed}, {"not_implemented", false}, {"cases", json::array()}};
}

void addCase(json& check, const std::string& function, json input, json output) {
    check["cases"].push_back({{"function", function}, {"input", std::move(input)}, {"output", std::move(output)}});
}

json callStage(const std::function<json()>& call) {
    try {
        return call();
    } catch (const NotImplemented&) {
        throw;
    } catch (const std::exception& e) {
        return {{"error", e.what()}};
    }
}

probe::ProbeVolume randomVolume(CheckRandom& rng, glm::ivec3 dims, glm::dvec3 spacing, double scale, double offset) {
    probe::ProbeVolume volume;
    volume.dims = dims;
    volume.extent = glm::vec3(glm::dvec3(dims) * spacing);
    volume.values.resize(std::size_t(dims.x) * dims.y * dims.z);
    for (float& v : volume.values) v = float(rng.uniform());
    volume.valueScale = float(scale);
    volume.valueOffset = float(offset);
    return volume;
}

json volumeJson(const probe::ProbeVolume& volume) {
    json values = json::array();
    for (float v : volume.values) values.push_back(double(v));
    return {{"dims", {volume.dims.x, volume.dims.y, volume.dims.z}},
            {"extent", vecJson(glm::dvec3(volume.extent))},
            {"value_scale", double(volume.valueScale)},
            {"value_offset", double(volume.valueOffset)},
            {"values", values},
            {"layout", "x fastest; voxel (i,j,k) is centred at (i+1/2, j+1/2, k+1/2) * extent / dims; "
                       "value = values * value_scale + value_offset"}};
}

probe::ProbeResults marchRays(const std::string& root, const std::string& fragment,
                              const probe::ProbeVolume& volume, const std::vector<ProbeRay>& rays,
                              const std::function<void(const ShaderProgram&, int)>& perCase) {
    std::vector<glm::vec4> origins, directions;
    for (const ProbeRay& r : rays) {
        origins.push_back(texel(r.origin, r.tEntry));
        directions.push_back(texel(r.direction, r.tExit));
    }
    GlslProbe probe(root, fragment, kMarchConstants);
    probe.setVolume(volume);
    return probe.run(kCases, {origins, directions}, perCase);
}

double probeField(const probe::ProbeVolume& v, glm::dvec3 p) {
    const glm::dvec3 u = p / glm::dvec3(v.extent) * glm::dvec3(v.dims) - 0.5;
    const glm::dvec3 lower = glm::floor(u), w = u - lower;
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 corner(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        const glm::ivec3 ijk = glm::clamp(glm::ivec3(lower) + corner, glm::ivec3(0), v.dims - 1);
        const double weight = (corner.x ? w.x : 1.0 - w.x) * (corner.y ? w.y : 1.0 - w.y) * (corner.z ? w.z : 1.0 - w.z);
        sum += weight * double(v.values[std::size_t((ijk.z * v.dims.y + ijk.y) * v.dims.x + ijk.x)]);
    }
    return sum * v.valueScale + v.valueOffset;
}

ProbeRay boxRay(CheckRandom& rng, glm::dvec3 extent, glm::dvec3 through, double back) {
    ProbeRay ray;
    ray.direction = unitF32(rng.unitVector());
    ray.origin = f32(through - back * ray.direction);
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const double d = ray.direction[a];
        if (d == 0.0) continue;  // the origin lies between this axis's planes (through does)
        const double ta = -ray.origin[a] / d, tb = (extent[a] - ray.origin[a]) / d;
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    ray.tEntry = f32(t0);
    ray.tExit = f32(t1);
    return ray;
}

ProbeRay marchingRay(CheckRandom& rng, glm::dvec3 extent, std::size_t i) {
    const bool inside = i % 4 == 3;
    const glm::dvec3 through = rng.inBox(0.05 * extent, 0.95 * extent);
    const double back = inside ? rng.range(0.0, 1.0) : glm::length(extent) + rng.range(0.1, 2.0);
    return boxRay(rng, extent, through, back);
}

double sampleT(const ProbeRay& ray, double step, int m) { return ray.tEntry + (m + 0.5) * step; }

int clearSampleCount(const ProbeRay& ray, double step) {
    const double x = (ray.tExit - ray.tEntry) / step + 0.5;
    if (std::abs(x - std::round(x)) < kCountMargin) return -1;
    return int(std::floor(x));
}

json rayInput(const ProbeRay& ray, double step) {
    return {{"origin", vecJson(ray.origin)}, {"direction", vecJson(ray.direction)}, {"t_entry", ray.tEntry},
            {"t_exit", ray.tExit}, {"step", step}};
}

json probeFlag(float v) { return std::isfinite(v) ? json(v != 0.0f) : json(nullptr); }

void randomRays(CheckRandom& rng, glm::dvec3 extent, std::vector<ProbeRay>* rays, std::vector<double>* steps,
                const std::function<void()>& accepted) {
    while (int(rays->size()) < kCases) {
        const ProbeRay ray = marchingRay(rng, extent, rays->size());
        const double step = f32(rng.range(0.2, 0.9));
        if (clearSampleCount(ray, step) < 1) continue;
        rays->push_back(ray);
        steps->push_back(step);
        if (accepted) accepted();
    }
}

json runProjection(const std::string& root, const std::string& stage, const std::string& function, std::uint32_t seed,
                   double (*skew)(double u)) {
    CheckRandom rng(seed);
    probe::ProbeVolume volume = randomVolume(rng, glm::ivec3(6, 7, 5), glm::dvec3(1.3, 0.8, 1.1), 65535.0, -32768.0);
    // Skewed so that many rays' results are negative for MIP (most values
    // low) and positive for MinIP (most values high): a maximum that starts
    // at 0, or a minimum that does, fails many cases. Whole int16 values.
    for (float& v : volume.values) {
        const double u = skew ? skew(double(v)) : double(v);
        v = float(std::round(u * 65535.0) / 65535.0);
    }
    volume.linearFilter = true;
    std::vector<ProbeRay> rays;
    std::vector<double> steps;
    randomRays(rng, glm::dvec3(volume.extent), &rays, &steps);
    const probe::ProbeResults results =
        marchRays(root, "stages/" + stage + "/" + stage + "_probe.frag", volume, rays,
                  [&](const ShaderProgram& program, int i) { program.set("u_step", float(steps[std::size_t(i)])); });
    json check = checkJson(stage + "_random_rays", stage, rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}, {"interpolation", "hardware"}};
    for (std::size_t k = 0; k < rays.size(); ++k)
        addCase(check, function, rayInput(rays[k], steps[k]), {{"value", number(results.first[k].x)}});
    check["not_implemented"] = results.notImplemented;
    return check;
}

double notANumber() { return std::numeric_limits<double>::quiet_NaN(); }

CaseVerdict failure(const std::string& note) { return {false, notANumber(), note}; }

bool isFiniteNumber(const json& j) { return j.is_number() && std::isfinite(j.get<double>()); }

CaseVerdict compareNumbers(const json& expected, const json& actual, double absolute, double relative) {
    if (expected.is_number()) {
        if (!isFiniteNumber(actual)) return failure(actual.is_null() ? "NaN" : "not a number");
        const double e = expected.get<double>(), a = actual.get<double>();
        const double delta = std::abs(a - e);
        return {delta <= absolute + relative * std::abs(e), delta, ""};
    }
    if (!expected.is_array() || !actual.is_array() || actual.size() != expected.size())
        return failure("wrong number of components");
    CaseVerdict v;
    for (std::size_t k = 0; k < expected.size(); ++k) {
        const CaseVerdict c = compareNumbers(expected[k], actual[k], absolute, relative);
        if (!c.pass && v.pass) v.note = c.note;
        v.pass = v.pass && c.pass;
        v.delta = std::isnan(c.delta) || std::isnan(v.delta) ? notANumber() : std::max(v.delta, c.delta);
    }
    return v;
}

CaseVerdict compareExact(const json& expected, const json& actual) {
    return expected == actual ? CaseVerdict{} : failure("");
}

bool readPoints(const json& list, std::vector<glm::dvec3>* points) {
    if (!list.is_array()) return false;
    for (const json& p : list) {
        if (!p.is_array() || p.size() != 3 || !isFiniteNumber(p[0]) || !isFiniteNumber(p[1]) || !isFiniteNumber(p[2]))
            return false;
        points->push_back(vecOf(p));
    }
    return true;
}

CaseVerdict compareHitFlags(const json& e, const json& a, bool* bothHit) {
    *bothHit = false;
    if (!a.is_object() || !a.contains("hit") || !a["hit"].is_boolean()) return failure("no hit flag");
    if (a["hit"] != e["hit"]) return failure(e["hit"] == true ? "missed" : "a hit where there is none");
    *bothHit = e["hit"] == true;
    return {};
}

CaseVerdict compareProjection(const std::string&, const json&, const json& e, const json& a) {
    return compareNumbers(e.at("value"), a.value("value", json()), 8.0, 0.0);
}

ProbeTransferFunction randomTransferFunction(CheckRandom& rng) {
    ProbeTransferFunction tf;
    std::vector<int> values = {0, 100};
    for (int n = 1 + rng.index(5); n > 0; --n) values.push_back(1 + rng.index(99));
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    for (int v : values) {
        const double alpha = rng.index(6) == 0 ? 0.0 : rng.index(6) == 0 ? 1.0 : rng.range(0.0, 1.0);
        tf.points.push_back({v, glm::vec4(glm::vec3(f32(rng.inBox(glm::dvec3(0.0), glm::dvec3(1.0)))), float(alpha))});
    }
    for (int i = 0; i <= 100; ++i) {
        std::size_t k = 0;
        while (tf.points[k + 1].first < i) ++k;
        const auto& [v0, c0] = tf.points[k];
        const auto& [v1, c1] = tf.points[k + 1];
        tf.table.push_back(glm::mix(c0, c1, float(i - v0) / float(v1 - v0)));
    }
    return tf;
}

json transferFunctionJson(const ProbeTransferFunction& tf) {
    json points = json::array();
    for (const auto& [value, c] : tf.points)
        points.push_back({{"value", value}, {"color", vecJson(glm::dvec3(glm::vec3(c)))}, {"alpha", double(c.a)}});
    return points;
}

}  // namespace voxlab::check
