// voxlab stage tf2d: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

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
    GlslProbe probe(root, "stages/tf2d/tf2d_probe.frag");
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

CaseVerdict compareTf2d(const std::string&, const json&, const json& e, const json& a) {
    // Colour and opacity in [0, 1], a few float operations: 1e-4.
    return compareNumbers(e, a, 1e-4, 0.0);
}

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(tf2d) {
    using namespace voxlab::check;
    checks.add("tf2d_classify_random",
               "tf2d_classify() with 1 to 4 random triangle and box widgets, at random (value, gradient) pairs: "
               "inside widgets, at a triangle's apex, on a box's edge",
               runTf2d, compareTf2d);
}
