// voxlab stage shading: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

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
    GlslProbe probe(root, "stages/shading/phong_probe.frag");
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

// Per-check tolerances. Each one forgives a different order of float
// operations (another correct formula), nothing more; the inputs keep away
// from the places where a function jumps (see the top of this file).
CaseVerdict comparePhong(const std::string&, const json&, const json& e, const json& a) {
    // Colours of order 1; pow(x, 128) turns a relative rounding error of
    // 1e-7 in x into 1.3e-5: 2e-4 + 1e-4 |e| per channel.
    return compareNumbers(e, a, 2e-4, 1e-4);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(shading) {
    using namespace voxlab::check;
    checks.add("phong_random",
               "phong() on random unit normals, lights and views, Phong and Blinn-Phong, lights behind the surface "
               "and grazing it",
               runPhong, comparePhong);
}
