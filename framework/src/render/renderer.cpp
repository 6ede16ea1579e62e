// voxlab: parameter checking shared by every renderer, and the registry.
#include "voxlab/renderer.h"

#include <cmath>
#include <cstdio>

#include "voxlab/error.h"
#include "voxlab/shader.h"

namespace voxlab {

const char* parameterTypeName(ParameterType t) {
    switch (t) {
        case ParameterType::Float: return "float";
        case ParameterType::Int: return "int";
        case ParameterType::Bool: return "bool";
    }
    return "?";
}

void Renderer::setUniforms(const ShaderProgram& program, const ParameterValues& values) const {
    for (const ParameterSpec& p : parameters()) {
        const std::string name = "u_" + p.name;
        const double v = values.at(p.name);
        if (p.type == ParameterType::Float)
            program.set(name.c_str(), float(v));
        else
            program.set(name.c_str(), int(v));
    }
}

std::vector<ParameterSpec> Renderer::parametersFor(glm::dvec2 dataRange) const {
    std::vector<ParameterSpec> specs = parameters();
    for (ParameterSpec& p : specs) {
        if (!p.scaledByData()) continue;
        const double origin = p.dataUnits ? dataRange.x : 0.0;  // a value, or a difference of values
        const auto toData = [&](double f) { return origin + f * (dataRange.y - dataRange.x); };
        p.minValue = toData(p.minValue);
        p.maxValue = toData(p.maxValue);
        p.defaultValue = toData(p.defaultValue);
    }
    return specs;
}

void Renderer::draw(DrawContext&, const ParameterValues&) const {}

void Renderer::checkScene(const Scene& scene, const ParameterValues&) const {
    if (scene.labels) throw Error(id() + ": does not draw label maps (scene \"labels\"; the compositing renderer does)");
    if (scene.fusion) throw Error(id() + ": does not draw a fused second volume (scene \"fusion\"; the compositing renderer does)");
}

BrickCombine Renderer::brickCombine(const ParameterValues&) const { return BrickCombine::None; }

bool parameterOn(const ParameterValues& values, const std::string& name) {
    const auto it = values.find(name);
    return it != values.end() && it->second != 0.0;
}

namespace {

// The estimator the parameters `sobel` and `precomputed_gradients` choose,
// and whether it is precomputed.
std::pair<GradientEstimator, bool> gradientChoice(const ParameterValues& values) {
    return {parameterOn(values, "sobel") ? GradientEstimator::Sobel : GradientEstimator::Central,
            parameterOn(values, "precomputed_gradients")};
}

}  // namespace

std::optional<GradientEstimator> Renderer::precomputedGradients(const ParameterValues& values) const {
    const auto [estimator, precomputed] = gradientChoice(values);
    return precomputed ? std::optional<GradientEstimator>(estimator) : std::nullopt;
}

std::optional<GradientEstimator> Renderer::onTheFlyGradients(const ParameterValues& values) const {
    const auto [estimator, precomputed] = gradientChoice(values);
    return precomputed ? std::nullopt : std::optional<GradientEstimator>(estimator);
}

EmptySpaceRule Renderer::emptySpaceRule(const ParameterValues&) const { return {}; }

std::vector<Precomputation> Renderer::precomputations(const Scene&, const Volume&, const ParameterValues&) const {
    return {};
}

ParameterValues Renderer::resolveParameters(const ParameterValues& given,
                                            std::optional<glm::dvec2> dataRange) const {
    const std::vector<ParameterSpec> specs = dataRange ? parametersFor(*dataRange) : parameters();
    ParameterValues out;
    for (const ParameterSpec& p : specs) out[p.name] = p.defaultValue;
    for (const auto& [name, value] : given) {
        const ParameterSpec* spec = nullptr;
        for (const ParameterSpec& p : specs)
            if (p.name == name) spec = &p;
        if (!spec) {
            std::string known;
            for (const ParameterSpec& p : specs) known += (known.empty() ? "" : ", ") + p.name;
            throw Error(id() + ": parameter '" + name + "' is not declared (" +
                        (known.empty() ? "it has none" : "it has: " + known) + ")");
        }
        const std::string where = id() + ": parameter '" + name + "'";
        if (!std::isfinite(value)) throw Error(where + " must be a finite number");
        if (spec->type == ParameterType::Bool && value != 0.0 && value != 1.0)
            throw Error(where + " is a bool (0/1, true/false)");
        if (spec->type == ParameterType::Int && value != std::floor(value))
            throw Error(where + " must be an integer");
        if (spec->scaledByData() && !dataRange) {
            out[name] = value;
            continue;
        }
        if (value < spec->minValue || value > spec->maxValue) {
            char msg[160];
            std::snprintf(msg, sizeof msg, " = %g is outside [%g, %g]", value, spec->minValue, spec->maxValue);
            throw Error(where + msg);
        }
        out[name] = value;
    }
    return out;
}

const Renderer* RendererRegistry::find(const std::string& id) const {
    for (const auto& r : renderers_)
        if (r->id() == id) return r.get();
    return nullptr;
}

const Renderer& RendererRegistry::get(const std::string& id) const {
    if (const Renderer* r = find(id)) return *r;
    std::string names;
    for (const auto& r : renderers_) names += (names.empty() ? "" : ", ") + r->id();
    throw Error("unknown renderer '" + id + "' (available: " + names + ")");
}

}  // namespace voxlab
