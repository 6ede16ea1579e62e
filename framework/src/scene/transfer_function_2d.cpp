// voxlab: the 2D transfer function's widgets, evaluation and JSON
// (see transfer_function_2d.h for the formulas).
#include "voxlab/transfer_function_2d.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "json_text.h"
#include "voxlab/error.h"

namespace voxlab {

namespace {

using json = nlohmann::json;
using json_text::shortFloat;

bool inUnit(double x) { return std::isfinite(x) && x >= 0.0 && x <= 1.0; }

// Opacity of one widget at (f, g).
double widgetAlpha(const Tf2dWidget& w, double f, double g) {
    if (w.kind == Tf2dWidget::Kind::Box) {
        const bool inside = f >= w.valueRange.x && f <= w.valueRange.y && g >= w.gradientRange.x &&
                            g <= w.gradientRange.y;
        return inside ? w.alpha : 0.0;
    }
    const double fv = w.valueRange.x, distance = std::abs(fv - f);
    if (g <= 0.0) return distance == 0.0 ? w.alpha : 0.0;
    if (distance > w.radius * g) return 0.0;
    return w.alpha * (1.0 - distance / (w.radius * g));
}

void check(const Tf2dWidget& w, const std::string& at) {
    if (!inUnit(w.alpha)) throw Error(at + ".alpha: expected a number in 0..1");
    for (int k = 0; k < 3; ++k)
        if (!inUnit(w.color[k])) throw Error(at + ".color: expected an array of 3 numbers in 0..1");
    if (w.kind == Tf2dWidget::Kind::Triangle) {
        if (!std::isfinite(w.valueRange.x)) throw Error(at + ".value: expected a number");
        if (!(std::isfinite(w.radius) && w.radius > 0.0)) throw Error(at + ".radius: expected a number > 0");
    } else {
        if (!(w.valueRange.y >= w.valueRange.x)) throw Error(at + ".value: expected [lo, hi] with hi >= lo");
        if (!(w.gradientRange.y >= w.gradientRange.x && w.gradientRange.x >= 0.0))
            throw Error(at + ".gradient: expected [lo, hi] with 0 <= lo <= hi");
    }
}

double number(const json& j, const std::string& at) {
    if (!j.is_number() || !std::isfinite(j.get<double>())) throw Error(at + ": expected a number");
    return j.get<double>();
}

glm::dvec2 pair(const json& j, const std::string& at) {
    if (!j.is_array() || j.size() != 2) throw Error(at + ": expected [lo, hi]");
    return {number(j[0], at + "[0]"), number(j[1], at + "[1]")};
}

Tf2dWidget parseWidget(const json& j, const std::string& at) {
    if (!j.is_object()) throw Error(at + ": expected an object with \"type\": \"triangle\" or \"box\"");
    if (!j.contains("type") || !j["type"].is_string())
        throw Error(at + ".type: missing (\"triangle\" or \"box\")");
    const std::string type = j["type"].get<std::string>();
    Tf2dWidget w;
    std::vector<std::string> keys = {"type", "color", "alpha", "value"};
    if (type == "triangle") {
        w.kind = Tf2dWidget::Kind::Triangle;
        keys.push_back("radius");
    } else if (type == "box") {
        w.kind = Tf2dWidget::Kind::Box;
        keys.push_back("gradient");
    } else {
        throw Error(at + ".type: unknown widget type '" + type + "' (expected triangle or box)");
    }
    for (const auto& item : j.items())
        if (std::find(keys.begin(), keys.end(), item.key()) == keys.end())
            throw Error(at + "." + item.key() + ": unknown key for a " + type + " widget");
    for (const std::string& key : keys)
        if (!j.contains(key)) throw Error(at + ": missing key '" + key + "'");

    const json& c = j["color"];
    if (!c.is_array() || c.size() != 3) throw Error(at + ".color: expected an array of 3 numbers in 0..1");
    for (int k = 0; k < 3; ++k) w.color[k] = float(number(c[k], at + ".color"));
    w.alpha = float(number(j["alpha"], at + ".alpha"));
    if (w.kind == Tf2dWidget::Kind::Triangle) {
        w.valueRange = glm::dvec2(number(j["value"], at + ".value"));
        w.radius = number(j["radius"], at + ".radius");
    } else {
        w.valueRange = pair(j["value"], at + ".value");
        w.gradientRange = pair(j["gradient"], at + ".gradient");
    }
    check(w, at);
    return w;
}

}  // namespace

bool Tf2dWidget::operator==(const Tf2dWidget& o) const {
    return kind == o.kind && valueRange == o.valueRange && radius == o.radius &&
           gradientRange == o.gradientRange && color == o.color && alpha == o.alpha;
}

TransferFunction2D::TransferFunction2D(std::vector<Tf2dWidget> widgets) : widgets_(std::move(widgets)) {
    if (int(widgets_.size()) > kMaxTf2dWidgets)
        throw Error("2D transfer function: " + std::to_string(widgets_.size()) + " widgets (at most " +
                    std::to_string(kMaxTf2dWidgets) + ")");
    for (std::size_t i = 0; i < widgets_.size(); ++i)
        check(widgets_[i], "2D transfer function: widgets[" + std::to_string(i) + "]");
}

glm::vec4 TransferFunction2D::evaluate(double f, double g) const {
    double keep = 1.0, weight = 0.0;
    glm::dvec3 colour(0.0);
    for (const Tf2dWidget& w : widgets_) {
        const double a = widgetAlpha(w, f, g);
        keep *= 1.0 - a;
        weight += a;
        colour += a * glm::dvec3(w.color);
    }
    if (weight <= 0.0) return glm::vec4(0.0f);
    return glm::vec4(glm::vec3(colour / weight), float(1.0 - keep));
}

namespace {

TransferFunction2D parseFunction(const json& j, const std::string& where, const std::string& key) {
    const std::string at = (where.empty() ? "" : where + ": ") + (key.empty() ? "" : key);
    const std::string dot = key.empty() ? "" : ".";
    if (!j.is_object() || !j.contains("widgets"))
        throw Error(at + (key.empty() ? "" : ": ") + "expected an object {\"widgets\": [...]}");
    for (const auto& item : j.items())
        if (item.key() != "widgets") throw Error(at + dot + item.key() + ": unknown key");
    const json& list = j["widgets"];
    if (!list.is_array()) throw Error(at + dot + "widgets: expected an array of widgets");
    if (int(list.size()) > kMaxTf2dWidgets)
        throw Error(at + dot + "widgets: " + std::to_string(list.size()) + " widgets (at most " +
                    std::to_string(kMaxTf2dWidgets) + ")");
    std::vector<Tf2dWidget> widgets;
    for (std::size_t i = 0; i < list.size(); ++i)
        widgets.push_back(parseWidget(list[i], at + dot + "widgets[" + std::to_string(i) + "]"));
    return TransferFunction2D(std::move(widgets));
}

}  // namespace

TransferFunction2D TransferFunction2D::fromJson(const json& j, const std::string& where, const std::string& key) {
    return json_text::escapedErrors([&] { return parseFunction(j, where, key); });
}

TransferFunction2D TransferFunction2D::load(const std::string& path) {
    return fromJson(json_text::readJsonFile(path), path);
}

json TransferFunction2D::toJson() const {
    json list = json::array();
    for (const Tf2dWidget& w : widgets_) {
        json o;
        o["type"] = w.kind == Tf2dWidget::Kind::Triangle ? "triangle" : "box";
        if (w.kind == Tf2dWidget::Kind::Triangle) {
            o["value"] = w.valueRange.x;
            o["radius"] = w.radius;
        } else {
            o["value"] = {w.valueRange.x, w.valueRange.y};
            o["gradient"] = {w.gradientRange.x, w.gradientRange.y};
        }
        o["color"] = {shortFloat(w.color.r), shortFloat(w.color.g), shortFloat(w.color.b)};
        o["alpha"] = shortFloat(w.alpha);
        list.push_back(o);
    }
    return {{"widgets", list}};
}

}  // namespace voxlab
