// voxlab: the 1D transfer function: exact evaluation, baking into a lookup
// table with a proven error bound, and JSON input/output.
#include "voxlab/transfer_function.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

#include "json_text.h"
#include "voxlab/error.h"

namespace voxlab {

namespace {

using json = nlohmann::json;

glm::dvec4 toD(const ControlPoint& p) { return glm::dvec4(glm::dvec3(p.color), double(p.alpha)); }

bool inUnit(double x) { return std::isfinite(x) && x >= 0.0 && x <= 1.0; }

// "where: " or nothing, so that messages still read well without a file name.
std::string prefix(const std::string& where) { return where.empty() ? "" : where + ": "; }

using json_text::shortFloat;

// One control point from JSON; `at` is its location ("tf.json: points[2]").
ControlPoint parsePoint(const json& j, const std::string& at) {
    if (!j.is_object()) throw Error(at + ": expected an object {\"value\", \"color\", \"alpha\"}");
    for (const auto& item : j.items())
        if (item.key() != "value" && item.key() != "color" && item.key() != "alpha")
            throw Error(at + ": unknown key '" + item.key() + "'");
    for (const char* key : {"value", "color", "alpha"})
        if (!j.contains(key)) throw Error(at + ": missing key '" + key + "'");

    ControlPoint p;
    const json& v = j.at("value");
    if (!v.is_number() || !std::isfinite(v.get<double>()))
        throw Error(at + ".value: expected a number");
    p.value = v.get<double>();

    const json& c = j.at("color");
    const std::string colorError = at + ".color: expected an array of 3 numbers in 0..1";
    if (!c.is_array() || c.size() != 3) throw Error(colorError);
    for (int k = 0; k < 3; ++k) {
        if (!c[k].is_number() || !inUnit(c[k].get<double>())) throw Error(colorError);
        p.color[k] = c[k].get<float>();
    }

    const json& a = j.at("alpha");
    if (!a.is_number() || !inUnit(a.get<double>())) throw Error(at + ".alpha: expected a number in 0..1");
    p.alpha = a.get<float>();
    return p;
}

// "N control points (at most 65536)", the one wording for every place that
// counts them.
std::string tooManyPoints(std::size_t n) {
    return std::to_string(n) + " control points (at most " + std::to_string(kMaxTransferFunctionPoints) + ")";
}

}  // namespace

TransferFunction::TransferFunction(std::vector<ControlPoint> points) : points_(std::move(points)) {
    if (points_.size() > kMaxTransferFunctionPoints)
        throw Error("transfer function: " + tooManyPoints(points_.size()));
    for (size_t i = 0; i < points_.size(); ++i) {
        const ControlPoint& p = points_[i];
        const std::string at = "transfer function: control point " + std::to_string(i);
        if (!std::isfinite(p.value)) throw Error(at + ": value is not a finite number");
        for (int k = 0; k < 3; ++k)
            if (!inUnit(p.color[k])) throw Error(at + ": colour outside 0..1");
        if (!inUnit(p.alpha)) throw Error(at + ": alpha outside 0..1");
    }
    std::stable_sort(points_.begin(), points_.end(),
                     [](const ControlPoint& a, const ControlPoint& b) { return a.value < b.value; });
}

glm::vec4 TransferFunction::evaluate(double v) const {
    if (points_.empty()) return glm::vec4(0.0f);
    // Clamped outside the points (NaN is treated like "below").
    if (!(v >= points_.front().value)) return glm::vec4(toD(points_.front()));
    if (v >= points_.back().value) return glm::vec4(toD(points_.back()));
    // b is the first point beyond v, a the last point at or below it; among
    // equal values (a step) that is the later one, as documented.
    const auto b = std::upper_bound(points_.begin(), points_.end(), v,
                                    [](double x, const ControlPoint& p) { return x < p.value; });
    const auto a = b - 1;
    const double t = (v - a->value) / (b->value - a->value);
    return glm::vec4(toD(*a) + (toD(*b) - toD(*a)) * t);
}

glm::vec4 TransferFunctionTable::lookup(double v) const {
    if (size <= 0 || rgba.empty()) return glm::vec4(0.0f);
    if (size == 1 || !(hi > lo)) return rgba.front();
    // Texel-centre coordinate, as GL_LINEAR computes it for the texture
    // coordinate documented in the header: u*size - 0.5 = x*(size-1).
    const double x = std::clamp(std::isnan(v) ? lo : v, lo, hi);
    const double t = (x - lo) * (size - 1) / (hi - lo);
    const int i = std::min(int(t), size - 2);
    const double f = t - i;
    return glm::vec4(glm::dvec4(rgba[i]) * (1.0 - f) + glm::dvec4(rgba[i + 1]) * f);
}

TransferFunctionTable TransferFunction::bake(double lo, double hi, double tolerance,
                                             int maxSize) const {
    if (!std::isfinite(lo) || !std::isfinite(hi))
        throw Error("transfer function: cannot bake over a non-finite range");
    TransferFunctionTable table;
    table.lo = lo;
    if (!(hi > lo)) {  // degenerate: one value, stored as a constant table
        table.hi = lo + 1.0;
        table.size = 2;
        table.rgba.assign(2, evaluate(lo));
        table.maxError = 0.0;
        return table;
    }
    table.hi = hi;
    maxSize = std::max(maxSize, 2);

    for (int size = std::min(256, maxSize);; size = int(std::min(2LL * size, (long long)maxSize))) {
        table.size = size;
        table.rgba.resize(size);
        for (int i = 0; i < size; ++i) table.rgba[i] = evaluate(lo + (hi - lo) * i / (size - 1));

        // The error (table minus exact function) is piecewise linear with
        // kinks only at entry positions, where it is zero, and at control
        // values; so its maximum over [lo, hi] is found at the control values,
        // on both sides of a step.
        double worst = 0.0;
        for (size_t k = 0; k < points_.size(); ++k) {
            const double c = points_[k].value;
            if (c < lo || c > hi) continue;
            // The function's value here (the right side of a step) and, when
            // c > lo, the left limit: the first point of a group at c.
            if (k > 0 && points_[k - 1].value == c) continue;
            const glm::dvec4 t(table.lookup(c));
            const glm::dvec4 right = glm::abs(t - glm::dvec4(evaluate(c)));
            const glm::dvec4 left = c > lo ? glm::abs(t - toD(points_[k])) : glm::dvec4(0.0);
            worst = std::max({worst, right.x, right.y, right.z, right.w, left.x, left.y, left.z, left.w});
        }
        table.maxError = worst;
        if (worst <= tolerance || size >= maxSize) return table;
    }
}

TransferFunction TransferFunction::fromJson(const json& j, const std::string& where) {
    return fromJson(j, where, "");
}

namespace {

TransferFunction parseFunction(const json& j, const std::string& where, const std::string& key) {
    // Labels: a file's points are "points[i]"; under a scene key they are
    // "key[i]" (array form) or "key.points[i]" (object form).
    const std::string pre = prefix(where);
    const json* arr = &j;
    std::string label = key.empty() ? "points" : key;
    if (j.is_object()) {
        const std::string objAt = pre + (key.empty() ? "" : key + ": ");
        for (const auto& item : j.items()) {
            if (item.key() == "points") continue;
            if (item.key() != "name" && item.key() != "description")
                throw Error(objAt + "unknown key '" + item.key() + "'");
            if (!item.value().is_string())
                throw Error(pre + (key.empty() ? "" : key + ".") + item.key() + ": expected a string");
        }
        if (!j.contains("points")) throw Error(objAt + "missing key 'points'");
        arr = &j.at("points");
        label = key.empty() ? "points" : key + ".points";
    } else if (!j.is_array()) {
        throw Error(pre + (key.empty() ? "" : key + ": ") +
                    "expected an array of control points or an object {\"points\": [...]}");
    }
    if (!arr->is_array()) throw Error(pre + label + ": expected an array of control points");
    if (arr->empty()) throw Error(pre + label + ": expected at least 1 control point");
    if (arr->size() > kMaxTransferFunctionPoints) throw Error(pre + label + ": " + tooManyPoints(arr->size()));

    std::vector<ControlPoint> points;
    for (size_t i = 0; i < arr->size(); ++i)
        points.push_back(parsePoint((*arr)[i], pre + label + "[" + std::to_string(i) + "]"));
    return TransferFunction(std::move(points));
}

}  // namespace

TransferFunction TransferFunction::fromJson(const json& j, const std::string& where,
                                            const std::string& key) {
    return json_text::escapedErrors([&] { return parseFunction(j, where, key); });
}

TransferFunction TransferFunction::load(const std::string& path) {
    const json j = json_text::readJsonFile(path);
    return fromJson(j, path);
}

json TransferFunction::toJson() const {
    json arr = json::array();
    for (const ControlPoint& p : points_) {
        arr.push_back({{"value", p.value},
                       {"color", {shortFloat(p.color.r), shortFloat(p.color.g), shortFloat(p.color.b)}},
                       {"alpha", shortFloat(p.alpha)}});
    }
    return arr;
}

TransferFunction TransferFunction::ramp(double lo, double hi) {
    return TransferFunction({{lo, glm::vec3(1.0f), 0.0f}, {hi, glm::vec3(1.0f), 1.0f}});
}

TransferFunction defaultCompositingFunction(glm::dvec2 window) {
    return TransferFunction({{window.x, glm::vec3(1.0f), 0.0f}, {window.y, glm::vec3(1.0f), 0.1f}});
}

}  // namespace voxlab
