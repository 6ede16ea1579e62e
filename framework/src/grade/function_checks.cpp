// voxlab: function-level checks for the grader (see function_checks.h).
//
// Every check draws its inputs from its own std::mt19937 with a fixed seed.
// Raw 32-bit outputs are turned into numbers here (uniform() below), never
// by <random>'s distributions, whose results the standard leaves to each
// library, and from no transcendental function (whose last bit varies
// between C libraries). Every random number is drawn in a statement of its
// own or in a braced list (whose order C++ fixes), and every input is then
// rounded (to float, or to a grid of powers of two), so that rounding
// differences between compilers (a fused multiply-add) almost never show.
// GLSL inputs are stored as the floats the GPU computed with.
//
// Random inputs stay away from the places where a function jumps (a flag
// that flips where a dot product is 0, a voxel boundary for nearest
// neighbour, a box widget's edge), except where a case puts an input
// exactly on such a place on purpose, in exact arithmetic: there the
// documented rule (">= 0 is inside", "ties go to the lower axis") decides,
// and an implementation that rounds differently elsewhere cannot lose.
#include "voxlab/function_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <random>

#include "glsl_probe.h"
#include "voxlab/error.h"
#include "voxlab/scene.h"
#include "voxlab/stage_library.h"

namespace voxlab {
namespace {

using json = nlohmann::json;
using probe::GlslProbe;

constexpr int kCases = 200;

// ---------------------------------------------------------------------------
// Inputs

class CheckRandom {
public:
    explicit CheckRandom(std::uint32_t seed) : engine_(seed), seed_(seed) {}
    std::uint32_t seed() const { return seed_; }
    // [0, 1): mt19937's outputs are 32-bit integers, the same on every platform.
    double uniform() { return double(std::uint32_t(engine_())) / 4294967296.0; }
    double range(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    int index(int n) { return int(std::uint32_t(engine_()) % std::uint32_t(n)); }
    glm::dvec3 inBox(glm::dvec3 lo, glm::dvec3 hi) { return {range(lo.x, hi.x), range(lo.y, hi.y), range(lo.z, hi.z)}; }
    // Uniform on the sphere: a point of the cube, kept when inside the ball.
    glm::dvec3 unitVector() {
        for (;;) {
            const glm::dvec3 p = inBox(glm::dvec3(-1.0), glm::dvec3(1.0));
            const double length = glm::length(p);
            if (length > 0.1 && length <= 1.0) return p / length;
        }
    }

private:
    std::mt19937 engine_;
    std::uint32_t seed_;
};

double f32(double x) { return double(float(x)); }
glm::dvec3 f32(glm::dvec3 v) { return glm::dvec3(glm::vec3(v)); }
glm::dvec3 unitF32(glm::dvec3 v) { return f32(glm::normalize(v)); }
glm::vec4 texel(glm::dvec3 v, double w = 0.0) { return glm::vec4(glm::vec3(v), float(w)); }

json vecJson(glm::dvec3 v) { return json::array({v.x, v.y, v.z}); }
glm::dvec3 vecOf(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

// Outputs: a NaN or an infinity becomes null here already, so a result
// reads the same before and after a trip through a file.
json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }
json numbers(std::initializer_list<float> values) {
    json a = json::array();
    for (float v : values) a.push_back(number(v));
    return a;
}

// `seed` is recorded so that a failing case can be reproduced (the report shows it).
json checkJson(const std::string& name, const std::string& stage, std::uint32_t seed) {
    return {{"check", name}, {"stage", stage}, {"seed", seed}, {"not_implemented", false}, {"cases", json::array()}};
}

void addCase(json& check, const std::string& function, json input, json output) {
    check["cases"].push_back({{"function", function}, {"input", std::move(input)}, {"output", std::move(output)}});
}

std::string checkedRoot(const std::string& implementationRoot) {
    if (implementationRoot.empty()) return projectRoot() + "/reference";
    if (!std::filesystem::is_directory(implementationRoot))
        throw Error("implementation root '" + implementationRoot + "' is not a folder");
    return implementationRoot;
}

// A C++ stage's call: NotImplemented propagates (the stage is a stub);
// any other exception is that case's output, and fails it.
json callStage(const std::function<json()>& call) {
    try {
        return call();
    } catch (const NotImplemented&) {
        throw;
    } catch (const std::exception& e) {
        return {{"error", e.what()}};
    }
}

// ---------------------------------------------------------------------------
// phong_random (stage shading)

// The normal, light and view of case `kind` of the Phong check: where the
// light reaches the surface (n.l > 0), where it does not (n.l < 0: no
// highlight even with the viewer at the mirror direction), grazing exactly
// (n.l = 0 in float), and views near the mirror direction
// r = 2 (n.l) n - l, where the highlight is.
void phongDirections(CheckRandom& rng, int kind, glm::dvec3& n, glm::dvec3& l, glm::dvec3& v) {
    for (;;) {
        n = unitF32(rng.unitVector());
        l = unitF32(rng.unitVector());
        if (kind == 3) {
            // n along an axis and l across it: n.l is exactly 0.
            const int axis = rng.index(3);
            n = glm::dvec3(0.0);
            n[axis] = rng.index(2) ? 1.0 : -1.0;
            l[axis] = 0.0;
            l = unitF32(l);
            l[axis] = 0.0;
        } else if (kind != 4) {
            const double nl = glm::dot(n, l);
            if (std::abs(nl) < 0.05) continue;
            if ((kind == 2) != (nl < 0.0)) l = -l;
        }
        const glm::dvec3 mirror = 2.0 * glm::dot(n, l) * n - l;
        if (kind == 0) {
            v = rng.unitVector();
            if (glm::dot(v, n) < 0.0) v = -v;
        } else if (kind == 4) {
            v = rng.unitVector();
        } else {
            const double spread = rng.range(0.0, 0.35);
            v = mirror + spread * rng.unitVector();
        }
        if (glm::length(v) < 0.1) continue;
        v = unitF32(v);
        if (kind != 3 && std::abs(glm::dot(n, l)) < 1e-3) continue;
        if (glm::length(l + v) < 0.1) continue;  // Blinn's half vector would be undefined
        break;
    }
}

json runPhong(const std::string& root) {
    struct Coefficients {
        double ka, kd, ks, shininess;
        int blinn;
    };
    CheckRandom rng(0x5EED0001u);
    std::vector<glm::vec4> colours, normals, lights, views;
    std::vector<Coefficients> coefficients;
    json check = checkJson("phong_random", "shading", rng.seed());
    std::vector<json> inputs;
    for (int i = 0; i < kCases; ++i) {
        Coefficients c;
        c.blinn = i % 2;
        c.ka = f32(rng.range(0.05, 0.4));
        c.kd = f32(rng.range(0.2, 0.9));
        c.ks = f32(rng.range(0.1, 1.0));
        const double u = rng.uniform();
        c.shininess = f32(1.0 + 127.0 * u * u);  // 1 to 128, more often low
        const glm::dvec3 colour = f32(rng.inBox(glm::dvec3(0.1), glm::dvec3(1.0)));
        glm::dvec3 n, l, v;
        phongDirections(rng, (i / 2) % 5, n, l, v);
        colours.push_back(texel(colour));
        normals.push_back(texel(n));
        lights.push_back(texel(l));
        views.push_back(texel(v));
        coefficients.push_back(c);
        inputs.push_back({{"colour", vecJson(colour)}, {"normal", vecJson(n)}, {"light", vecJson(l)},
                          {"view", vecJson(v)}, {"ka", c.ka}, {"kd", c.kd}, {"ks", c.ks},
                          {"shininess", c.shininess}, {"blinn", c.blinn}});
    }
    GlslProbe probe(root, "probes/phong_probe.frag");
    const probe::ProbeResults results =
        probe.run(kCases, {colours, normals, lights, views}, [&](const ShaderProgram& program, int i) {
            const Coefficients& c = coefficients[std::size_t(i)];
            program.set("u_ka", float(c.ka));
            program.set("u_kd", float(c.kd));
            program.set("u_ks", float(c.ks));
            program.set("u_shininess", float(c.shininess));
            program.set("u_blinn", c.blinn);
        });
    for (int i = 0; i < kCases; ++i) {
        const glm::vec4 r = results.first[std::size_t(i)];
        addCase(check, "phong", inputs[std::size_t(i)], numbers({r.r, r.g, r.b}));
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

// ---------------------------------------------------------------------------
// Volumes for trilinear_random_points and gradient_random_points

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

// ---------------------------------------------------------------------------
// trilinear_random_points (stage sampling)

json runTrilinear(const std::string& root) {
    CheckRandom rng(0x5EED0002u);
    const glm::ivec3 dims(7, 5, 6);
    const probe::ProbeVolume volume = randomVolume(rng, dims, glm::dvec3(0.8, 1.3, 1.0), 2.0, -0.5);
    const glm::dvec3 extent(volume.extent), spacing = extent / glm::dvec3(dims);
    std::vector<glm::vec4> points;
    for (int i = 0; i < kCases; ++i) {
        glm::dvec3 p;
        switch (i % 4) {
        case 0:  // anywhere in the box
            p = rng.inBox(glm::dvec3(0.0), extent);
            break;
        case 1: {  // near a face, or on it
            p = rng.inBox(glm::dvec3(0.0), extent);
            const int axis = rng.index(3);
            const double inset = rng.index(2) == 0 ? 0.0 : rng.range(0.0, 0.02) * spacing[axis];
            p[axis] = rng.index(2) ? extent[axis] - inset : inset;
            break;
        }
        case 2: {  // on a voxel centre
            const glm::dvec3 voxel{double(rng.index(dims.x)), double(rng.index(dims.y)), double(rng.index(dims.z))};
            p = (voxel + 0.5) * spacing;
            break;
        }
        default: {  // up to half a voxel outside a face: the border value continues
            p = rng.inBox(glm::dvec3(0.0), extent);
            const int axis = rng.index(3);
            const double outside = rng.range(0.001, 0.5) * spacing[axis];
            p[axis] = rng.index(2) ? extent[axis] + outside : -outside;
        }
        }
        // Nearest neighbour jumps at the voxel boundaries inside the grid:
        // keep a thousandth of a voxel away from them.
        for (int a = 0; a < 3; ++a) {
            const double c = p[a] / spacing[a], k = std::round(c);
            if (k >= 1.0 && k <= dims[a] - 1.0 && std::abs(c - k) < 1e-3) p[a] += 2e-3 * spacing[a];
        }
        points.push_back(texel(f32(p)));
    }
    GlslProbe probe(root, "probes/sampling_probe.frag");
    probe.setVolume(volume);
    const probe::ProbeResults results = probe.run(kCases, {points});
    json check = checkJson("trilinear_random_points", "sampling", rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}};
    for (int f = 0; f < 2; ++f)
        for (int i = 0; i < kCases; ++i) {
            const glm::vec4 r = results.first[std::size_t(i)];
            addCase(check, f == 0 ? "sample_trilinear" : "sample_nearest",
                    {{"point", vecJson(glm::dvec3(glm::vec3(points[std::size_t(i)])))}}, number(f == 0 ? r.x : r.y));
        }
    check["not_implemented"] = results.notImplemented;
    return check;
}

// ---------------------------------------------------------------------------
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
    GlslProbe probe(root, "probes/cubic_probe.frag", {{"u_interpolation", 4}});
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

// ---------------------------------------------------------------------------
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
    GlslProbe probe(root, "probes/gradient_probe.frag", {{"u_interpolation", 2}});
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

// ---------------------------------------------------------------------------
// half_space_random (stage cutting_plane)

json runHalfSpace(const std::string& root) {
    CheckRandom rng(0x5EED0004u);
    std::vector<glm::vec4> planePoints, planeNormals, tested, origins, directions;
    for (int i = 0; i < kCases; ++i) {
        // Kinds: 0, 1 a random plane; 2 an axis-aligned plane and a ray
        // parallel to it; 3 an axis-aligned plane and a point exactly on it.
        const int kind = i % 4;
        const int axis = rng.index(3);
        glm::dvec3 normal = unitF32(rng.unitVector());
        if (kind >= 2) {
            normal = glm::dvec3(0.0);
            normal[axis] = rng.index(2) ? 1.0 : -1.0;
        }
        const glm::dvec3 point = f32(rng.inBox(glm::dvec3(-1.0), glm::dvec3(2.0)));
        glm::dvec3 p;
        for (;;) {
            p = f32(rng.inBox(glm::dvec3(-2.0), glm::dvec3(3.0)));
            if (kind == 3) p[axis] = point[axis];
            if (kind == 3 || std::abs(glm::dot(p - point, normal)) >= 1e-3) break;
        }
        glm::dvec3 origin, direction;
        double tEntry, tExit;
        for (;;) {
            origin = f32(rng.inBox(glm::dvec3(-2.0), glm::dvec3(3.0)));
            direction = rng.unitVector();
            if (kind == 2) direction[axis] = 0.0;
            if (glm::length(direction) < 0.1) continue;
            direction = unitF32(direction);
            if (kind == 2) direction[axis] = 0.0;
            tEntry = f32(rng.range(0.0, 2.0));
            tExit = f32(tEntry + rng.range(0.05, 4.0));
            const double along = glm::dot(direction, normal), start = glm::dot(origin - point, normal);
            if (std::abs(start) < 1e-3) continue;
            if (kind == 2) break;
            if (std::abs(along) < 0.05) continue;
            const double crossing = -start / along;
            if (std::abs(crossing - tEntry) >= 1e-3 && std::abs(crossing - tExit) >= 1e-3) break;
        }
        planePoints.push_back(texel(point));
        planeNormals.push_back(texel(normal));
        tested.push_back(texel(p));
        origins.push_back(texel(origin, tEntry));
        directions.push_back(texel(direction, tExit));
    }
    GlslProbe probe(root, "probes/half_space_probe.frag");
    const probe::ProbeResults results = probe.run(kCases, {planePoints, planeNormals, tested, origins, directions});
    json check = checkJson("half_space_random", "cutting_plane", rng.seed());
    auto flag = [](float v) { return std::isfinite(v) ? json(v != 0.0f) : json(nullptr); };
    for (int i = 0; i < kCases; ++i) {
        const std::size_t k = std::size_t(i);
        addCase(check, "in_half_space",
                {{"p", vecJson(glm::vec3(tested[k]))},
                 {"point", vecJson(glm::vec3(planePoints[k]))},
                 {"normal", vecJson(glm::vec3(planeNormals[k]))}},
                flag(results.first[k].x));
    }
    for (int i = 0; i < kCases; ++i) {
        const std::size_t k = std::size_t(i);
        const glm::vec4 r = results.first[k];
        addCase(check, "clip_to_half_space",
                {{"origin", vecJson(glm::vec3(origins[k]))},
                 {"direction", vecJson(glm::vec3(directions[k]))},
                 {"t_entry", double(origins[k].w)},
                 {"t_exit", double(directions[k].w)},
                 {"point", vecJson(glm::vec3(planePoints[k]))},
                 {"normal", vecJson(glm::vec3(planeNormals[k]))}},
                {{"kept", flag(r.y)}, {"t_entry", number(r.z)}, {"t_exit", number(r.w)}});
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

// ---------------------------------------------------------------------------
// tf2d_classify_random (stage tf2d)

struct Tf2dProbeWidget {
    bool box = false;
    glm::dvec4 shape{0.0};  // as the shader gets it (tf2d_widgets.glsl)
    glm::dvec3 colour{0.0};
    double alpha = 0.0;
};

// The widget in the JSON form of voxlab/transfer_function_2d.h.
json widgetJson(const Tf2dProbeWidget& w) {
    if (w.box)
        return {{"type", "box"}, {"value", {w.shape.x, w.shape.y}}, {"gradient", {w.shape.z, w.shape.w}},
                {"alpha", w.alpha}, {"color", vecJson(w.colour)}};
    return {{"type", "triangle"}, {"value", w.shape.x}, {"radius", w.shape.y}, {"alpha", w.alpha},
            {"color", vecJson(w.colour)}};
}

// A random set of one to four widgets for the tf2d check.
std::vector<Tf2dProbeWidget> randomTf2dWidgets(CheckRandom& rng) {
    std::vector<Tf2dProbeWidget> widgets(std::size_t(1 + rng.index(4)));
    for (Tf2dProbeWidget& w : widgets) {
        w.box = rng.index(2) == 1;
        if (w.box) {
            const double v0 = f32(rng.range(0.0, 80.0)), g0 = rng.index(3) == 0 ? 0.0 : f32(rng.range(0.0, 10.0));
            w.shape = {v0, f32(v0 + rng.range(5.0, 40.0)), g0, f32(g0 + rng.range(2.0, 15.0))};
        } else {
            w.shape = {f32(rng.range(10.0, 90.0)), f32(rng.range(0.5, 3.0)), 0.0, 0.0};
        }
        w.colour = f32(rng.inBox(glm::dvec3(0.0), glm::dvec3(1.0)));
        w.alpha = rng.index(8) == 0 ? 1.0 : f32(rng.range(0.1, 1.0));
    }
    return widgets;
}

// A (value, gradient) point for case `kind` of the tf2d check. Kinds: 0
// anywhere; 1, 4 inside a chosen widget; 2 on the value axis (g = 0), at a
// triangle's apex or not; 3 exactly on a box's edge.
glm::vec4 tf2dPoint(CheckRandom& rng, const std::vector<Tf2dProbeWidget>& widgets, int kind) {
    std::size_t pick = std::size_t(rng.index(int(widgets.size())));
    if (kind == 2)  // at an apex: prefer a triangle
        for (std::size_t k = 0; k < widgets.size(); ++k)
            if (!widgets[k].box) pick = k;
    const Tf2dProbeWidget& chosen = widgets[pick];
    double f = 0.0, g = 0.0;
    for (int attempt = 0;; ++attempt) {
        f = f32(rng.range(0.0, 100.0));
        g = f32(rng.range(0.0, 25.0));
        const glm::dvec4 s = chosen.shape;
        if (kind == 1 || kind == 4) {
            if (chosen.box) {
                f = f32(rng.range(s.x, s.y));
                g = f32(rng.range(s.z, s.w));
            } else {
                g = f32(rng.range(0.5, 20.0));
                f = f32(s.x + rng.range(-1.0, 1.0) * s.y * g);
            }
        } else if (kind == 2) {
            g = 0.0;
            if (!chosen.box && rng.index(2) == 0) f = s.x;
        } else if (kind == 3 && chosen.box) {
            const int edge = rng.index(4);
            if (edge < 2) {
                f = edge == 0 ? s.x : s.y;
                g = f32(rng.range(s.z, s.w));
            } else {
                f = f32(rng.range(s.x, s.y));
                g = edge == 2 ? s.z : s.w;
            }
        }
        // Keep off the boxes' edges, where the opacity jumps, unless
        // exactly on one.
        auto near = [](double x, double edge) { return x != edge && std::abs(x - edge) < 1e-3; };
        bool nearEdge = false;
        for (const Tf2dProbeWidget& w : widgets)
            if (w.box)
                nearEdge = nearEdge || near(f, w.shape.x) || near(f, w.shape.y) || near(g, w.shape.z) ||
                           near(g, w.shape.w);
        if (!nearEdge || attempt > 100) break;
    }
    return glm::vec4(float(f), float(g), 0.0f, 0.0f);
}

json runTf2d(const std::string& root) {
    CheckRandom rng(0x5EED0005u);
    std::vector<std::vector<Tf2dProbeWidget>> widgetSets;
    std::vector<glm::vec4> points;
    for (int i = 0; i < kCases; ++i) {
        std::vector<Tf2dProbeWidget> widgets = randomTf2dWidgets(rng);
        points.push_back(tf2dPoint(rng, widgets, i % 5));
        widgetSets.push_back(std::move(widgets));
    }
    GlslProbe probe(root, "probes/tf2d_probe.frag");
    const probe::ProbeResults results = probe.run(kCases, {points}, [&](const ShaderProgram& program, int i) {
        const std::vector<Tf2dProbeWidget>& widgets = widgetSets[std::size_t(i)];
        program.set("u_tf2d_count", int(widgets.size()));
        for (std::size_t k = 0; k < widgets.size(); ++k) {
            const std::string index = "[" + std::to_string(k) + "]";
            program.set(("u_tf2d_kind" + index).c_str(), widgets[k].box ? 1 : 0);
            program.set(("u_tf2d_shape" + index).c_str(), glm::vec4(widgets[k].shape));
            program.set(("u_tf2d_color" + index).c_str(), glm::vec4(glm::vec3(widgets[k].colour), widgets[k].alpha));
        }
    });
    json check = checkJson("tf2d_classify_random", "tf2d", rng.seed());
    for (int i = 0; i < kCases; ++i) {
        const std::size_t k = std::size_t(i);
        json widgets = json::array();
        for (const Tf2dProbeWidget& w : widgetSets[k]) widgets.push_back(widgetJson(w));
        const glm::vec4 r = results.first[k];
        addCase(check, "tf2d_classify",
                {{"value", double(points[k].x)}, {"gradient", double(points[k].y)}, {"widgets", widgets}},
                numbers({r.r, r.g, r.b, r.a}));
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

// ---------------------------------------------------------------------------
// marching_cubes_random (stage marching_cubes, C++): cubeCase on random
// corner values (some exactly at the isovalue, all above, all below) and
// edgeCrossing on random edges crossed either way.

json runMarchingCubes(const std::string&) {
    CheckRandom rng(0x5EED0014u);
    json check = checkJson("marching_cubes_random", "marching_cubes", rng.seed());
    for (int i = 0; i < kCases; ++i) {
        const double iso = f32(rng.range(-100.0, 100.0));
        double values[8];
        for (double& v : values) v = f32(iso + rng.range(-50.0, 50.0));
        if (i % 4 == 1)  // corners exactly at the isovalue count as inside
            for (double& v : values)
                if (rng.index(3) == 0) v = iso;
        if (i % 16 == 2)
            for (double& v : values) v = iso + 1.0;  // every corner inside: 255
        if (i % 16 == 3)
            for (double& v : values) v = iso - 1.0;  // none: 0
        json corners = json::array();
        for (double v : values) corners.push_back(v);
        addCase(check, "cubeCase", {{"values", corners}, {"isovalue", iso}},
                callStage([&] { return json(cppStages().cubeCase(values, iso)); }));
    }
    for (int i = 0; i < kCases; ++i) {
        const glm::dvec3 a = f32(rng.inBox(glm::dvec3(-50.0), glm::dvec3(50.0)));
        const glm::dvec3 b = f32(a + rng.unitVector() * rng.range(0.3, 4.0));
        const double iso = f32(rng.range(-10.0, 10.0));
        double below = f32(iso - rng.range(0.01, 30.0)), above = f32(iso + rng.range(0.01, 30.0));
        if (i % 8 == 5) above = iso;  // the upper corner exactly at the isovalue: the vertex is there
        if (rng.index(2)) std::swap(below, above);  // crossed either way
        addCase(check, "edgeCrossing",
                {{"a", vecJson(a)}, {"b", vecJson(b)}, {"va", below}, {"vb", above}, {"isovalue", iso}},
                callStage([&] { return vecJson(cppStages().edgeCrossing(a, b, below, above, iso)); }));
    }
    check["not_implemented"] = false;
    return check;
}

// ---------------------------------------------------------------------------
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

// ---------------------------------------------------------------------------
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

// ---------------------------------------------------------------------------
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
    GlslProbe probe(root, "probes/slice_opacity_probe.frag");
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

// ---------------------------------------------------------------------------
// plane_box_random (stage texslice3d)

// A grid point: v rounded to a multiple of `step` (see runPlaneBox).
glm::dvec3 onGrid(glm::dvec3 v, double step) { return glm::round(v / step) * step; }

// The plane (normal, offset: dot(n, p) = offset) of case `kind` of the
// plane-box check, for the box [lo, hi]; case `i` 5 gets a zero normal.
void randomPlane(CheckRandom& rng, int kind, int i, glm::dvec3 lo, glm::dvec3 hi, glm::dvec3& normal,
                 double& offset) {
    const double diagonal = glm::length(hi - lo);
    auto boxCorner = [&](int bits) {  // bit k set: the high side on axis k
        return glm::dvec3(bits & 1 ? hi.x : lo.x, bits & 2 ? hi.y : lo.y, bits & 4 ? hi.z : lo.z);
    };
    auto randomNormal = [&]() {
        for (;;) {
            const glm::dvec3 n = onGrid(rng.unitVector(), 1.0 / 256.0);
            if (n != glm::dvec3(0.0)) return n;
        }
    };
    // Whether every corner keeps a distance from the plane (random
    // planes must not pass "almost" through a corner).
    auto clearOfCorners = [&](glm::dvec3 n, double d) {
        for (int c = 0; c < 8; ++c)
            if (std::abs(glm::dot(n, boxCorner(c)) - d) < 1e-4 * diagonal * glm::length(n)) return false;
        return true;
    };
    for (;;) {
        normal = randomNormal();
        if (kind == 0) {  // through a random point of the box
            offset = glm::dot(normal, onGrid(rng.inBox(lo, hi), 1.0 / 1024.0));
        } else if (kind == 1) {  // parallel to a face: inside, or containing the face
            const int axis = rng.index(3), where = rng.index(3);
            normal = glm::dvec3(0.0);
            normal[axis] = rng.index(2) ? 1.0 : -1.0;
            const double at = where == 0 ? lo[axis] : where == 1 ? hi[axis]
                                                                  : onGrid(rng.inBox(lo, hi), 1.0 / 64.0)[axis];
            offset = normal[axis] * at;
            return;
        } else if (kind == 2) {  // through a corner: cutting the box there, or only touching it
            offset = glm::dot(normal, boxCorner(rng.index(8)));
            return;
        } else if (kind == 3) {  // containing an edge: through the box, or only touching it
            const int axis = rng.index(3);
            normal[axis] = 0.0;
            if (normal == glm::dvec3(0.0)) continue;
            offset = glm::dot(normal, boxCorner(rng.index(8)));
            return;
        } else if (kind == 4) {  // anywhere near the box, possibly missing it
            offset = glm::dot(normal, onGrid(rng.inBox(lo - 0.5 * (hi - lo), hi + 0.5 * (hi - lo)), 1.0 / 1024.0));
        } else {  // through the centre; once a zero normal
            if (i == 5) normal = glm::dvec3(0.0);
            offset = glm::dot(normal, 0.5 * (lo + hi));
            return;
        }
        if (clearOfCorners(normal, offset)) return;
    }
}

json runPlaneBox(const std::string&) {
    CheckRandom rng(0x5EED0007u);
    json check = checkJson("plane_box_random", "texslice3d", rng.seed());
    // Boxes on a grid of 1/64, normals on a grid of 1/256 and points on a
    // grid of 1/1024, scaled by powers of two: then every offset dot(n, p)
    // is exact in double, and a plane put through a corner or an edge
    // really passes through it.
    for (int i = 0; i < kCases; ++i) {
        // One box in ten far from the origin (2^20 away: the handout's
        // "absolute epsilons" pitfall); still exact on the grids.
        const glm::dvec3 far = i % 10 == 9 ? glm::dvec3(std::ldexp(rng.index(2) ? 1.0 : -1.0, 20)) : glm::dvec3(0.0);
        const glm::dvec3 lo = far + onGrid(rng.inBox(glm::dvec3(-2.0), glm::dvec3(2.0)), 1.0 / 64.0);
        const glm::dvec3 hi = lo + onGrid(rng.inBox(glm::dvec3(0.25), glm::dvec3(3.0)), 1.0 / 64.0);
        glm::dvec3 normal;
        double offset = 0.0;
        randomPlane(rng, i % 6, i, lo, hi, normal, offset);
        // The normal need not have unit length: scaled by 2^-10..2^10, and
        // one case in ten each by about 1e200 and 1e-300 (the handout's
        // extreme normals: |n| overflows or underflows when squared).
        const int exponent = i % 10 == 7 ? 664 : i % 10 == 8 ? -997 : rng.index(21) - 10;
        const double scale = std::ldexp(1.0, exponent);
        normal *= scale;
        offset *= scale;
        const json output = callStage([&] {
            json vertices = json::array();
            for (const glm::dvec3& v : cppStages().planeBoxPolygon(normal, offset, lo, hi))
                vertices.push_back({number(v.x), number(v.y), number(v.z)});
            return vertices;
        });
        addCase(check, "planeBoxPolygon",
                {{"normal", vecJson(normal)}, {"offset", offset}, {"lo", vecJson(lo)}, {"hi", vecJson(hi)}}, output);
    }
    return check;
}

// ---------------------------------------------------------------------------
// Rays for first_hit_random_rays and iso_hit_random_rays
//
// Both checks hand first_hit() or iso_hit() a Ray as clip_ray() leaves it
// (t_entry and t_exit where it enters and leaves the volume's box) and walk
// the README's samples t_entry + (m + 1/2) step. Their outputs jump where a
// sample's value equals the threshold or isovalue (the hit moves by a whole
// step) and where the number of samples changes, so each ray is drawn again
// until every value it reads keeps clear of those places: then a correct
// submission that rounds differently (t by accumulation, a midpoint as
// lo + (hi - lo)/2) gets the same hit, and only the hit's rounding differs.

// Programs for the marching probes: the GPU's filtering (as for the
// gradient check: the check sees this stage alone), skipping and sample
// counting off (the empty-space helpers return their argument).
const ShaderConstants kMarchConstants = {
    {"u_interpolation", 2}, {"u_skipping", 0}, {"u_count_samples", 0}, {"u_clip_plane", 0}};

// How close (data units) a value may come to the threshold or isovalue, and
// to the number of samples' jump (L / step + 1/2 an integer). A sample's
// position differs between correct implementations by ~1e-5 world units,
// its value by ~1e-5: 1e-3 leaves a factor of 100.
constexpr double kValueMargin = 1e-3;
constexpr double kCountMargin = 1e-3;

struct ProbeRay {
    glm::dvec3 origin{0.0}, direction{0.0};  // as the GPU gets them (floats)
    double tEntry = 0.0, tExit = 0.0;
};

// Runs a ray-marching probe (first hit, iso) on `rays` through `volume`:
// each case gets its ray's origin and t_entry, direction and t_exit.
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

// The probe volume's trilinear field in double, clamped to the border
// voxels: only to keep the inputs clear of jumps (see above).
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

// A random unit direction through `through` (inside the box [0, extent]),
// from `back` before it; t_entry and t_exit by the slab method in double,
// then rounded to float as the GPU gets them. t_entry is 0 where the origin
// lies inside the box, as clip_ray() leaves it.
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

// The i-th random ray of a marching check: every fourth starts inside the
// box (t_entry = 0), the others come from up to 2 units outside it.
ProbeRay marchingRay(CheckRandom& rng, glm::dvec3 extent, std::size_t i) {
    const bool inside = i % 4 == 3;
    const glm::dvec3 through = rng.inBox(0.05 * extent, 0.95 * extent);
    const double back = inside ? rng.range(0.0, 1.0) : glm::length(extent) + rng.range(0.1, 2.0);
    return boxRay(rng, extent, through, back);
}

double sampleT(const ProbeRay& ray, double step, int m) { return ray.tEntry + (m + 0.5) * step; }

// floor(L / step + 1/2) samples (ray.glsl), or -1 where L / step + 1/2 is
// within kCountMargin of an integer (float rounding could add or drop one).
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

// ---------------------------------------------------------------------------
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
        marchRays(root, "probes/first_hit_probe.frag", volume, rays, [&](const ShaderProgram& program, int i) {
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

// ---------------------------------------------------------------------------
// mip_random_rays, minip_random_rays, average_random_rays (stages mip,
// minip, average): the projection of random rays through random int16 data
// (the whole range -32768..32767, negative values included, as the MIP
// handout promises), with unequal spacings and random steps.

// kCases marching rays through a box of `extent`, each with a random step
// (0.2 to 0.9) that gives it at least one sample and no doubt about how
// many; `accepted`, when given, is called after each ray is kept (it may
// draw more numbers from `rng` for that ray).
void randomRays(CheckRandom& rng, glm::dvec3 extent, std::vector<ProbeRay>* rays, std::vector<double>* steps,
                const std::function<void()>& accepted = nullptr) {
    while (int(rays->size()) < kCases) {
        const ProbeRay ray = marchingRay(rng, extent, rays->size());
        const double step = f32(rng.range(0.2, 0.9));
        if (clearSampleCount(ray, step) < 1) continue;
        rays->push_back(ray);
        steps->push_back(step);
        if (accepted) accepted();
    }
}

json runProjection(const std::string& root, const std::string& stage, const std::string& function, std::uint32_t seed) {
    CheckRandom rng(seed);
    probe::ProbeVolume volume = randomVolume(rng, glm::ivec3(6, 7, 5), glm::dvec3(1.3, 0.8, 1.1), 65535.0, -32768.0);
    // Skewed so that many rays' results are negative for MIP (most values
    // low) and positive for MinIP (most values high): a maximum that starts
    // at 0, or a minimum that does, fails many cases. Whole int16 values.
    for (float& v : volume.values) {
        const double u = stage == "mip" ? std::pow(double(v), 3.0) : stage == "minip" ? 1.0 - std::pow(double(v), 3.0) : v;
        v = float(std::round(u * 65535.0) / 65535.0);
    }
    volume.linearFilter = true;
    std::vector<ProbeRay> rays;
    std::vector<double> steps;
    randomRays(rng, glm::dvec3(volume.extent), &rays, &steps);
    const probe::ProbeResults results =
        marchRays(root, "probes/" + stage + "_probe.frag", volume, rays,
                  [&](const ShaderProgram& program, int i) { program.set("u_step", float(steps[std::size_t(i)])); });
    json check = checkJson(stage + "_random_rays", stage, rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}, {"interpolation", "hardware"}};
    for (std::size_t k = 0; k < rays.size(); ++k)
        addCase(check, function, rayInput(rays[k], steps[k]), {{"value", number(results.first[k].x)}});
    check["not_implemented"] = results.notImplemented;
    return check;
}

// attenuated_mip_random_rays (stage attenuated_mip): as the projections,
// with a random attenuation (0..0.5 per unit length of normalised
// intensity) and depth cue (0..0.1 per unit length) per ray; a quarter of
// the rays have one of them 0, so each term is also seen alone.
json runAttenuatedMipRays(const std::string& root) {
    CheckRandom rng(0x5EED0011u);
    probe::ProbeVolume volume = randomVolume(rng, glm::ivec3(6, 7, 5), glm::dvec3(1.3, 0.8, 1.1), 65535.0, -32768.0);
    for (float& v : volume.values) v = float(std::round(double(v) * 65535.0) / 65535.0);
    volume.linearFilter = true;
    const double minSpacing = f32(std::min({volume.extent.x / 6.0, volume.extent.y / 7.0, volume.extent.z / 5.0}));
    std::vector<ProbeRay> rays;
    std::vector<double> steps;
    std::vector<glm::dvec3> settings;  // step, attenuation, depth cue
    randomRays(rng, glm::dvec3(volume.extent), &rays, &steps, [&] {
        const int kind = int(settings.size()) % 4;
        settings.push_back({steps.back(), kind == 1 ? 0.0 : f32(rng.range(0.0, 0.5)), kind == 2 ? 0.0 : f32(rng.range(0.0, 0.1))});
    });
    const probe::ProbeResults results =
        marchRays(root, "probes/attenuated_mip_probe.frag", volume, rays, [&](const ShaderProgram& program, int i) {
            const glm::dvec3& c = settings[std::size_t(i)];
            program.set("u_step", float(c.x));
            program.set("u_step_units", float(c.x / minSpacing));
            program.set("u_attenuation", float(c.y));
            program.set("u_depth_cue", float(c.z));
        });
    json check = checkJson("attenuated_mip_random_rays", "attenuated_mip", rng.seed());
    check["fixture"] = {{"volume", volumeJson(volume)}, {"interpolation", "hardware"}, {"min_spacing", minSpacing}};
    for (std::size_t k = 0; k < rays.size(); ++k) {
        json input = rayInput(rays[k], settings[k].x);
        input["step_units"] = f32(settings[k].x / minSpacing);
        input["attenuation"] = settings[k].y;
        input["depth_cue"] = settings[k].z;
        input["units"] = "attenuation per unit length of intensity normalised to the volume's range, depth cue per "
                         "unit length; unit length = the smallest spacing";
        addCase(check, "attenuated_mip_ray", input, {{"value", number(results.first[k].x)}});
    }
    check["not_implemented"] = results.notImplemented;
    return check;
}

json runMipRays(const std::string& root) { return runProjection(root, "mip", "mip_ray", 0x5EED000Au); }
json runMinipRays(const std::string& root) { return runProjection(root, "minip", "minip_ray", 0x5EED000Bu); }
json runAverageRays(const std::string& root) { return runProjection(root, "average", "average_ray", 0x5EED000Cu); }

// ---------------------------------------------------------------------------
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
        marchRays(root, "probes/iso_hit_probe.frag", volume, rays, [&](const ShaderProgram& program, int i) {
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

// ---------------------------------------------------------------------------
// Comparison

double notANumber() { return std::numeric_limits<double>::quiet_NaN(); }

// One case's verdict: `delta` is the difference counted in "worst |Δ|"
// (NaN where it is not a number: a flag, a missing vertex).
struct CaseVerdict {
    bool pass = true;
    double delta = 0.0;
    std::string note;
};

CaseVerdict failure(const std::string& note) { return {false, notANumber(), note}; }

bool isFiniteNumber(const json& j) { return j.is_number() && std::isfinite(j.get<double>()); }

// Numbers, or arrays of them, agree where |a - e| <= absolute + relative |e|.
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

// The largest distance between matched vertices when actual[(start + step * i) mod n]
// is matched with expected[i].
double cycleDistance(const std::vector<glm::dvec3>& expected, const std::vector<glm::dvec3>& actual, int start,
                     int step) {
    const int n = int(expected.size());
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
        const int matched = ((start + step * i) % n + n) % n;
        worst = std::max(worst, glm::length(actual[std::size_t(matched)] - expected[std::size_t(i)]));
    }
    return worst;
}

// Polygons are cycles: the same vertices (within 1e-6 times the box's
// diagonal: the reference computes them to about 1e-15 of it, so this
// only forgives another order of floating-point operations) in the same
// cyclic order, from any starting vertex. The direction is part of the
// contract (counter-clockwise seen along the normal, proxy_geometry.h), so
// a reversed polygon fails, and so does an unsorted one.
CaseVerdict comparePolygons(const json& input, const json& expected, const json& actual) {
    const double tolerance = 1e-6 * glm::length(vecOf(input.at("hi")) - vecOf(input.at("lo")));
    std::vector<glm::dvec3> e, a;
    readPoints(expected, &e);
    if (!readPoints(actual, &a)) return failure("not a list of finite vertices");
    if (a.size() != e.size())
        return failure(std::to_string(a.size()) + " vertices instead of " + std::to_string(e.size()));
    const int n = int(e.size());
    if (n == 0) return {};
    double best = std::numeric_limits<double>::infinity(), reversed = best;
    for (int start = 0; start < n; ++start) {
        best = std::min(best, cycleDistance(e, a, start, 1));
        reversed = std::min(reversed, cycleDistance(e, a, start, -1));
    }
    if (best <= tolerance) return {true, best, ""};
    if (reversed <= tolerance) return failure("the right vertices in reverse (clockwise) order");
    double farthest = 0.0;  // from an expected vertex to the nearest vertex given
    for (const glm::dvec3& p : e) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const glm::dvec3& q : a) nearest = std::min(nearest, glm::length(p - q));
        farthest = std::max(farthest, nearest);
    }
    if (farthest <= tolerance) return failure("the right vertices in the wrong order");
    return {false, farthest, "other vertices"};
}

// Per-check tolerances. Each one forgives a different order of float
// operations (another correct formula), nothing more; the inputs keep away
// from the places where a function jumps (see the top of this file).
CaseVerdict comparePhong(const std::string&, const json&, const json& e, const json& a) {
    // Colours of order 1; pow(x, 128) turns a relative rounding error of
    // 1e-7 in x into 1.3e-5: 2e-4 + 1e-4 |e| per channel.
    return compareNumbers(e, a, 2e-4, 1e-4);
}

CaseVerdict compareSampling(const std::string& function, const json&, const json& e, const json& a) {
    // Values span [-0.5, 1.5]. Trilinear: weights and mixes in float, about
    // 1e-7 each, so 2e-5. Nearest returns a stored voxel value: 1e-6.
    return compareNumbers(e, a, function == "sample_nearest" ? 1e-6 : 2e-5, 0.0);
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

CaseVerdict compareCubic(const std::string& function, const json&, const json& e, const json& a) {
    // Weights: cubic polynomials of t in [0, 1) in float, of order 1: 1e-5.
    // Values span [-0.5, 1.5], 64 taps summed in float: 5e-5. Gradients of
    // order 1 to 10 per unit length, 64 products each: 5e-4 + 1e-4 |e|.
    if (function == "gradient_cubic") return compareNumbers(e, a, 5e-4, 1e-4);
    return compareNumbers(e, a, function == "sample_cubic" ? 5e-5 : 1e-5, 0.0);
}

CaseVerdict compareMarchingCubes(const std::string& function, const json&, const json& e, const json& a) {
    if (function == "cubeCase") return compareExact(e, a);  // a case number
    // A point from one division and one multiply-add in double, coordinates
    // up to 55: 1e-9 (1 + |x|).
    return compareNumbers(e, a, 1e-9, 1e-9);
}

CaseVerdict compareGradient(const std::string&, const json&, const json& e, const json& a) {
    // Gradients of order 1 to 10 per unit length; value differences in
    // float divided by distances of 0.35 to 2.4: 2e-4 + 1e-4 |e|.
    return compareNumbers(e, a, 2e-4, 1e-4);
}

CaseVerdict compareHalfSpace(const std::string& function, const json&, const json& e, const json& a) {
    if (function == "in_half_space") return compareExact(e, a);
    if (!a.is_object() || !a.contains("kept")) return failure("no result");
    if (a["kept"] != e["kept"]) return failure("kept is wrong");
    if (e["kept"] != true) return {};
    // Where something is kept, the interval: crossings are at least 1e-3
    // from the ends and |dot(direction, normal)| >= 0.05, so t is well
    // conditioned: 1e-4 (1 + |t|).
    return compareNumbers(json::array({e["t_entry"], e["t_exit"]}), json::array({a["t_entry"], a["t_exit"]}), 1e-4,
                          1e-4);
}

CaseVerdict compareTf2d(const std::string&, const json&, const json& e, const json& a) {
    // Colour and opacity in [0, 1], a few float operations: 1e-4.
    return compareNumbers(e, a, 1e-4, 0.0);
}

CaseVerdict compareSliceAxis(const std::string& function, const json&, const json& e, const json& a) {
    if (function == "chooseSliceAxis") return compareExact(e, a);  // an axis index, ties included
    // An opacity in [0, 1] from one pow(): 1e-4.
    return compareNumbers(e, a, 1e-4, 0.0);
}

CaseVerdict comparePlaneBox(const std::string&, const json& input, const json& e, const json& a) {
    return comparePolygons(input, e, a);
}

// The hit flags must agree; where neither hits, t and value are not part
// of the contract. *bothHit tells whether t must be compared.
CaseVerdict compareHitFlags(const json& e, const json& a, bool* bothHit) {
    *bothHit = false;
    if (!a.is_object() || !a.contains("hit") || !a["hit"].is_boolean()) return failure("no hit flag");
    if (a["hit"] != e["hit"]) return failure(e["hit"] == true ? "missed" : "a hit where there is none");
    *bothHit = e["hit"] == true;
    return {};
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

// The same samples give the same values; a sample's position differs
// between correct implementations by float rounding (~1e-5 units), its
// value by at most the largest slope (65535 per ~0.8 units) times that,
// about 1: 8 data units (1.2e-4 of the range) allows it, while a sample
// more or fewer, or one at the wrong place, moves a value by thousands.
CaseVerdict compareProjection(const std::string&, const json&, const json& e, const json& a) {
    return compareNumbers(e.at("value"), a.value("value", json()), 8.0, 0.0);
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
    GlslProbe probe(root, "probes/gradient_opacity_probe.frag");
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

// ---------------------------------------------------------------------------
// preintegrate_segment_random (stage preintegration)

// A random piecewise-linear transfer function over [0, 100]: control points
// at integer values (0 and 100 among them), so that its table of 101 entries,
// one per integer, is exact.
struct ProbeTransferFunction {
    std::vector<std::pair<int, glm::vec4>> points;  // value, (colour, opacity per unit length)
    std::vector<glm::vec4> table;                   // 101 entries
};

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

json runPreintegrateSegment(const std::string& root) {
    CheckRandom rng(0x5EED0012u);
    json check = checkJson("preintegrate_segment_random", "preintegration", rng.seed());
    GlslProbe probe(root, "probes/preintegration_probe.frag");
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

// ---------------------------------------------------------------------------
// light_transmittance_random (stage shadows)

json runLightTransmittance(const std::string& root) {
    CheckRandom rng(0x5EED0013u);
    json check = checkJson("light_transmittance_random", "shadows", rng.seed());
    // Values 0..100 in a 7x6x8 volume of unequal spacings (the smallest 0.6,
    // so the opacity correction's unit length is not 1).
    probe::ProbeVolume volume = randomVolume(rng, glm::ivec3(7, 6, 8), glm::dvec3(0.9, 0.6, 0.75), 100.0, 0.0);
    volume.linearFilter = true;
    const double minSpacing = 0.6;
    GlslProbe probe(root, "probes/light_transmittance_probe.frag", kMarchConstants);
    probe.setVolume(volume);
    check["fixture"] = {{"volume", volumeJson(volume)}, {"interpolation", "hardware"}, {"min_spacing", minSpacing}};
    constexpr int kFunctions = 4;
    bool notImplemented = false;
    for (int f = 0; f < kFunctions; ++f) {
        ProbeTransferFunction tf = randomTransferFunction(rng);
        // Faint opacities, so that light gets through several voxels.
        for (glm::vec4& e : tf.table) e.a *= f == 0 ? 1.0f : 0.25f;
        for (auto& point : tf.points) point.second.a *= f == 0 ? 1.0f : 0.25f;
        probe.setTransferFunction(tf.table, glm::vec2(0.0f, 100.0f));
        std::vector<glm::vec4> points, directions;
        for (int i = 0; i < kCases / kFunctions; ++i) {
            // Kinds: 0 anywhere inside; 1 on a face; 2 along an axis; 3 a
            // step larger than the box (one sample or none).
            const int kind = i % 4;
            glm::dvec3 p = f32(rng.inBox(glm::dvec3(0.0), glm::dvec3(volume.extent)));
            glm::dvec3 d = rng.unitVector();
            if (kind == 1) {
                const int axis = rng.index(3);
                p[axis] = rng.index(2) ? double(volume.extent[axis]) : 0.0;
            }
            if (kind == 2) {
                d = glm::dvec3(0.0);
                d[rng.index(3)] = rng.index(2) ? 1.0 : -1.0;
            }
            const double step = kind == 3 ? f32(rng.range(4.0, 8.0)) : f32(rng.range(0.1, 0.8));
            points.push_back(glm::vec4(glm::vec3(p), float(step)));
            directions.push_back(glm::vec4(glm::vec3(f32(d)), 0.0f));
        }
        const probe::ProbeResults results = probe.run(int(points.size()), {points, directions});
        notImplemented = notImplemented || results.notImplemented;
        const json tfJson = transferFunctionJson(tf);
        for (std::size_t k = 0; k < points.size(); ++k)
            addCase(check, "light_transmittance",
                    {{"p", vecJson(glm::dvec3(glm::vec3(points[k])))},
                     {"to_light", vecJson(glm::dvec3(glm::vec3(directions[k])))},
                     {"step", double(points[k].w)}, {"transfer_function", tfJson},
                     {"units", "p and step in world units; opacities per unit length (the smallest spacing)"}},
                    number(results.first[k].x));
    }
    check["not_implemented"] = notImplemented;
    return check;
}

CaseVerdict compareLightTransmittance(const std::string&, const json&, const json& e, const json& a) {
    // A product of up to ~150 factors, each rounded in float: 150 x 6e-8
    // ~ 1e-5 relative. 1e-4 also leaves room for stopping once T < 1e-3 (a
    // change below 1e-3 x 0.1 in the next factor... bounded by 1e-3 itself,
    // so stopping early is allowed by the absolute part). A shadow ray that
    // starts at p, runs away from the light or skips the correction is off
    // by far more on most cases.
    return compareNumbers(e, a, 1.1e-3, 1e-4);
}

// ---------------------------------------------------------------------------
// The list of checks

struct CheckDefinition {
    FunctionCheckInfo info;
    json (*run)(const std::string& implementationRoot);
    CaseVerdict (*compare)(const std::string& function, const json& input, const json& expected, const json& actual);
};

const std::vector<CheckDefinition>& definitions() {
    static const std::vector<CheckDefinition> list = {
        {{"phong_random", "shading",
          "phong() on random unit normals, lights and views, Phong and Blinn-Phong, lights behind the surface "
          "and grazing it"},
         runPhong, comparePhong},
        {{"trilinear_random_points", "sampling",
          "sample_trilinear() and sample_nearest() at random points of a random 7x5x6 volume with unequal "
          "spacings: inside, near and on the faces, on voxel centres, just outside"},
         runTrilinear, compareSampling},
        {{"gradient_random_points", "gradient",
          "gradient_central() and gradient_sobel() at random points of a random 6x7x5 volume with unequal "
          "spacings, near and on the faces included"},
         runGradient, compareGradient},
        {{"cubic_random_points", "cubic",
          "Catmull-Rom sample_cubic() and gradient_cubic() at random points of a random 7x6x5 volume with unequal "
          "spacings (near and on faces, on voxel centres), and cubic_weights() and cubic_derivative_weights() of "
          "both kernels at random fractions t"},
         runCubic, compareCubic},
        {{"marching_cubes_random", "marching_cubes",
          "cubeCase() on random corner values (some exactly at the isovalue, all above, all below) and "
          "edgeCrossing() on random edges crossed either way, one corner exactly at the isovalue on some"},
         runMarchingCubes, compareMarchingCubes},
        {{"splat_order_random", "splat",
          "splatOrder() on random view directions of any length, with two or three components tied exactly "
          "and with a zero component; axes and steps compared exactly"},
         runSplatOrder, [](const std::string&, const json&, const json& e, const json& a) { return compareExact(e, a); }},
        {{"shear_warp_random", "shearwarp",
          "factorShearWarp() for random orthographic cameras (any direction, zoom, pan, image size; axis views) "
          "over random grids with unequal spacings; axis, front slice and size exactly, shear, offset and warp "
          "within 1e-9 (1 + |x|)"},
         runShearWarp, compareShearWarp},
        {{"half_space_random", "cutting_plane",
          "in_half_space() and clip_to_half_space() on random planes, points and rays: points on the plane, "
          "rays parallel to it"},
         runHalfSpace, compareHalfSpace},
        {{"tf2d_classify_random", "tf2d",
          "tf2d_classify() with 1 to 4 random triangle and box widgets, at random (value, gradient) pairs: "
          "inside widgets, at a triangle's apex, on a box's edge"},
         runTf2d, compareTf2d},
        {{"slice_axis_random", "texslice2d",
          "chooseSliceAxis() on random directions with exact ties, and slice_opacity() on random slices"},
         runSliceAxis, compareSliceAxis},
        {{"plane_box_random", "texslice3d",
          "planeBoxPolygon() on random planes and boxes: through corners and edges, parallel to and containing "
          "faces, missing the box, normals of length ~1e200 and ~1e-300, boxes 2^20 from the origin; vertices "
          "compared as a counter-clockwise cycle"},
         runPlaneBox, comparePlaneBox},
        {{"first_hit_random_rays", "firsthit",
          "first_hit() on random rays through a random 7x6x8 volume, with random steps and thresholds: rays from "
          "outside the box and from inside it, hits and misses; t within 1e-4 (1 + |t|), far below half a step"},
         runFirstHit, compareFirstHit},
        {{"mip_random_rays", "mip",
          "mip_ray() on random rays through a random 6x7x5 volume of int16 values (-32768..32767) with unequal "
          "spacings and random steps: rays from outside the box and from inside it; values within 8"},
         runMipRays, compareProjection},
        {{"minip_random_rays", "minip",
          "minip_ray() on random rays through a random 6x7x5 volume of int16 values (-32768..32767) with unequal "
          "spacings and random steps: rays from outside the box and from inside it; values within 8"},
         runMinipRays, compareProjection},
        {{"average_random_rays", "average",
          "average_ray() on random rays through a random 6x7x5 volume of int16 values (-32768..32767) with "
          "unequal spacings and random steps: rays from outside the box and from inside it; values within 8"},
         runAverageRays, compareProjection},
        {{"iso_hit_random_rays", "iso",
          "iso_hit() on random rays through a bumpy ball, with random steps and 0 or 4 to 6 bisection steps: "
          "misses, hits from outside, rays starting inside; t within step / 2^(k+3) for k steps"},
         runIsoHit, compareIsoHit},
        {{"attenuated_mip_random_rays", "attenuated_mip",
          "attenuated_mip_ray() on random rays through a random 6x7x5 volume of int16 values with unequal spacings, "
          "random steps, attenuations and depth cues (each alone on a quarter of the rays); values within 8"},
         runAttenuatedMipRays, compareProjection},
        {{"gradient_opacity_random", "gradient_opacity",
          "gradient_opacity_weight() for random gradient magnitudes and bounds from 0.1 to 10^4 data units per "
          "unit length: below, inside and above the ramp, exactly on its bounds, equal and reversed bounds"},
         runGradientOpacity, compareGradientOpacity},
        {{"preintegrate_segment_random", "preintegration",
          "preintegrate_segment() for 4 random piecewise-linear transfer functions: random front and back values, "
          "lengths from 0.05 to 6 unit lengths and 1 to 200 sub-segments; one sub-segment, constant values, "
          "values beyond the function's range, segments across the whole range"},
         runPreintegrateSegment, comparePreintegrateSegment},
        {{"light_transmittance_random", "shadows",
          "light_transmittance() through a random 7x6x8 volume with unequal spacings (the smallest 0.6), 4 random "
          "transfer functions: random points inside and on faces, random and axis directions, steps from 0.1 to "
          "8 world units; within 1.1e-3 (stopping once T < 1e-3 is allowed)"},
         runLightTransmittance, compareLightTransmittance},
    };
    return list;
}

const CheckDefinition& definition(const std::string& name) {
    for (const CheckDefinition& d : definitions())
        if (d.info.name == name) return d;
    std::string known;
    for (const CheckDefinition& d : definitions()) known += (known.empty() ? "" : ", ") + d.info.name;
    throw Error("unknown function check '" + name + "' (known: " + known + ")");
}

// A short, readable form of inputs and outputs for the examples.
std::string brief(const json& j) {
    if (j.is_null()) return "NaN";
    if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
    if (j.is_number_integer()) return std::to_string(j.get<long long>());
    if (j.is_number()) {
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", j.get<double>());
        return text;
    }
    if (j.is_string()) return j.get<std::string>();
    std::string out;
    if (j.is_array()) {
        for (const json& item : j) out += (out.empty() ? "" : ", ") + brief(item);
        return "[" + out + "]";
    }
    for (const auto& item : j.items()) out += (out.empty() ? "" : ", ") + item.key() + " " + brief(item.value());
    return "{" + out + "}";
}

std::string formatDelta(double delta) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", delta);
    return text;
}

// What a student needs to rebuild a check's inputs: the seed, the random
// volume's dimensions, spacing and value mapping, and the units of it all.
json reproduction(const json& expected) {
    json out = json::object();
    if (expected.contains("seed") && expected["seed"].is_number_unsigned()) {
        char seed[16];
        std::snprintf(seed, sizeof seed, "0x%08X", expected["seed"].get<unsigned>());
        out["seed"] = seed;
    }
    const json volume = expected.value("fixture", json::object()).value("volume", json());
    if (!volume.is_object() || !volume.contains("dims") || !volume.contains("extent")) return out;
    const glm::dvec3 dims = vecOf(volume["dims"]), extent = vecOf(volume["extent"]);
    const glm::dvec3 spacing = extent / dims;
    const double offset = volume.value("value_offset", 0.0);
    char values[96];
    std::snprintf(values, sizeof values, "data value = stored value x %g %c %g", volume.value("value_scale", 1.0),
                  offset < 0 ? '-' : '+', std::abs(offset));
    const auto tidy = [](glm::dvec3 v) {  // floats as people write them: 1.3, not 1.3000000715
        return json::array({std::round(v.x * 1e6) / 1e6, std::round(v.y * 1e6) / 1e6, std::round(v.z * 1e6) / 1e6});
    };
    out["volume"] = {
        {"dims", volume["dims"]}, {"spacing", tidy(spacing)}, {"extent", tidy(extent)}, {"values", values}};
    out["units"] = "world units for points, origins, t, steps and extents (the volume's box is [0, extent] on "
                   "each axis, extent = dims x spacing, voxel (i, j, k) centred at (i+1/2, j+1/2, k+1/2) x "
                   "spacing); data units for values, thresholds and isovalues";
    return out;
}

}  // namespace

const std::vector<FunctionCheckInfo>& functionChecks() {
    static const std::vector<FunctionCheckInfo> infos = [] {
        std::vector<FunctionCheckInfo> list;
        for (const CheckDefinition& d : definitions()) list.push_back(d.info);
        return list;
    }();
    return infos;
}

json runFunctionCheck(const std::string& name, const std::string& implementationRoot) {
    const CheckDefinition& check = definition(name);
    return check.run(checkedRoot(implementationRoot));
}

CheckComparison compareFunctionCheck(const std::string& name, const json& expected, const json& actual) {
    const CheckDefinition& check = definition(name);
    const std::string where = "function check " + name + ": ";
    for (const json* j : {&expected, &actual}) {
        if (!j->is_object() || !j->contains("cases") || !(*j)["cases"].is_array())
            throw Error(where + "expected an object with a list of cases");
        if (j->value("check", std::string()) != name)
            throw Error(where + "the results are those of check '" + j->value("check", std::string("?")) + "'");
    }
    const json& expectedCases = expected["cases"];
    const json& actualCases = actual["cases"];
    const bool sameFixture = expected.value("fixture", json()) == actual.value("fixture", json());
    if (expectedCases.size() != actualCases.size() || !sameFixture)
        throw Error(where + "the expected and actual results were made from different inputs");

    CheckComparison result;
    result.cases = int(expectedCases.size());
    try {
        result.inputs = reproduction(expected);
    } catch (const json::exception&) {  // a fixture of another shape: nothing to say
    }
    double worst = 0.0, worstPassing = 0.0;
    std::map<std::string, std::pair<int, int>> perFunction;  // failed, cases
    for (std::size_t i = 0; i < expectedCases.size(); ++i) {
        const json& e = expectedCases[i];
        const json& a = actualCases[i];
        const std::string function = e.at("function").get<std::string>();
        const bool sameCase = a.is_object() && a.value("function", std::string()) == function &&
                              a.value("input", json()) == e.at("input");
        if (!sameCase)
            throw Error(where + "the expected and actual results were made from different inputs (case " +
                        std::to_string(i) + ")");
        const json& got = a.value("output", json());
        CaseVerdict verdict;
        if (got.is_object() && got.contains("error"))
            verdict = failure("threw: " + got["error"].get<std::string>());
        else
            verdict = check.compare(function, e["input"], e.at("output"), got);
        std::pair<int, int>& counts = perFunction[function];
        ++counts.second;
        if (verdict.pass) {
            worstPassing = std::max(worstPassing, verdict.delta);
            continue;
        }
        ++counts.first;
        ++result.failed;
        if (!std::isnan(verdict.delta)) worst = std::max(worst, verdict.delta);
        if (result.examples.size() < 3)
            result.examples.push_back(function + ", case " + std::to_string(i) + ": input " + brief(e["input"]) +
                                      "; expected " + brief(e["output"]) + "; got " + brief(got) +
                                      (verdict.note.empty() ? "" : " (" + verdict.note + ")"));
    }
    if (result.failed == 0) {
        result.summary = "all " + std::to_string(result.cases) + " cases agree";
        if (worstPassing > 0.0) result.summary += " (worst |\u0394| " + formatDelta(worstPassing) + ")";
        return result;
    }
    result.summary = std::to_string(result.failed) + " of " + std::to_string(result.cases) + " cases differ";
    if (perFunction.size() > 1) {
        std::string parts;
        for (const auto& [function, counts] : perFunction)
            if (counts.first > 0)
                parts += (parts.empty() ? "" : ", ") + function + " " + std::to_string(counts.first) + " of " +
                         std::to_string(counts.second);
        result.summary += " (" + parts + ")";
    }
    if (worst > 0.0) result.summary += "; worst |\u0394| " + formatDelta(worst);
    return result;
}

}  // namespace voxlab
