// voxlab: scene files. The schema is in scene.h; every error names the file
// and the key path ("scene.json: camera.azimut: unknown key").
#include "voxlab/scene.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>

#include <nlohmann/json.hpp>

#include "json_text.h"
#include "voxlab/error.h"

namespace voxlab {

const char* interpolationName(Interpolation i) {
    return i == Interpolation::Nearest ? "nearest" : "trilinear";
}

Interpolation parseInterpolation(const std::string& name) {
    if (name == "nearest") return Interpolation::Nearest;
    if (name == "trilinear") return Interpolation::Trilinear;
    throw Error("unknown interpolation '" + name + "' (expected nearest or trilinear)");
}

namespace {

using json = nlohmann::json;

// Reads one scene; `where` is the file name used in every message.
class Parser {
public:
    Parser(std::string where, std::string baseDir)
        : where_(std::move(where)), baseDir_(std::move(baseDir)) {}

    Scene parse(const json& j) const;

private:
    [[noreturn]] void fail(const std::string& key, const std::string& msg) const {
        throw Error((where_.empty() ? "" : where_ + ": ") + key + ": " + msg);
    }
    void onlyKeys(const json& obj, const std::string& path,
                  std::initializer_list<const char*> allowed) const {
        for (const auto& item : obj.items()) {
            bool ok = false;
            for (const char* a : allowed) ok = ok || item.key() == a;
            if (!ok) fail(path.empty() ? item.key() : path + "." + item.key(), "unknown key");
        }
    }
    double number(const json& j, const std::string& key) const {
        if (!j.is_number() || !std::isfinite(j.get<double>())) fail(key, "expected a number");
        return j.get<double>();
    }
    std::string string(const json& j, const std::string& key) const {
        if (!j.is_string()) fail(key, "expected a string");
        return j.get<std::string>();
    }
    // Runs f, adding this scene's location to any voxlab::Error it throws.
    template <class F>
    auto located(const std::string& key, F f) const {
        try {
            return f();
        } catch (const Error& e) {
            fail(key, e.what());
        }
    }

    void camera(const json& j, CameraSpec* cam) const;

    std::string where_, baseDir_;
};

void Parser::camera(const json& j, CameraSpec* cam) const {
    if (!j.is_object())
        fail("camera", "expected an object: {\"view\": \"+z\"} or azimuth/elevation/distance/fov/zoom");
    onlyKeys(j, "camera", {"view", "azimuth", "elevation", "distance", "fov", "zoom"});
    if (j.contains("view")) {
        for (const char* orbit : {"azimuth", "elevation", "distance", "fov"})
            if (j.contains(orbit))
                fail("camera", std::string("'view' cannot be combined with '") + orbit +
                                   "' (only with 'zoom')");
        cam->view = string(j["view"], "camera.view");
        if (!isAxisView(cam->view))
            fail("camera.view", "unknown view '" + cam->view + "' (expected +x -x +y -y +z -z)");
    }
    if (j.contains("azimuth")) cam->azimuth = number(j["azimuth"], "camera.azimuth");
    if (j.contains("elevation")) cam->elevation = number(j["elevation"], "camera.elevation");
    if (j.contains("distance")) {
        cam->distance = number(j["distance"], "camera.distance");
        if (cam->distance <= 0.0) fail("camera.distance", "expected a number > 0");
    }
    if (j.contains("fov")) {
        cam->fov = number(j["fov"], "camera.fov");
        if (cam->fov <= 0.0 || cam->fov >= 180.0) fail("camera.fov", "expected a number of degrees in (0, 180)");
    }
    if (j.contains("zoom")) {
        cam->zoom = number(j["zoom"], "camera.zoom");
        if (cam->zoom <= 0.0) fail("camera.zoom", "expected a number > 0");
    }
}

Scene Parser::parse(const json& j) const {
    if (!j.is_object()) throw Error((where_.empty() ? "" : where_ + ": ") + "expected a JSON object");
    onlyKeys(j, "", {"dataset", "renderer", "camera", "projection", "size", "sampling", "window",
                     "background", "parameters", "transfer_function"});
    Scene s;

    if (!j.contains("dataset")) fail("dataset", "missing (required)");
    const std::string dataset = string(j["dataset"], "dataset");
    s.dataset = located("dataset", [&] { return resolveDataPath(dataset, baseDir_); });

    if (j.contains("renderer")) {
        s.renderer = string(j["renderer"], "renderer");
        if (s.renderer.empty()) fail("renderer", "expected a renderer name");
    }

    if (j.contains("camera")) camera(j["camera"], &s.camera);
    // Axis views are mostly looked at orthographically; orbits in perspective.
    s.camera.projection = s.camera.view.empty() ? Projection::Perspective : Projection::Orthographic;
    if (j.contains("projection")) {
        const std::string p = string(j["projection"], "projection");
        s.camera.projection = located("projection", [&] { return parseProjection(p); });
    }

    if (j.contains("size")) {
        const json& size = j["size"];
        const std::string msg = "expected [width, height], integers in 1.." + std::to_string(kMaxImageSize);
        if (!size.is_array() || size.size() != 2) fail("size", msg);
        for (const json& n : size)
            if (!n.is_number_integer() || n.get<long long>() < 1 || n.get<long long>() > kMaxImageSize)
                fail("size", msg);
        s.width = size[0].get<int>();
        s.height = size[1].get<int>();
    }

    if (j.contains("sampling")) {
        const json& sampling = j["sampling"];
        if (!sampling.is_object()) fail("sampling", "expected an object {\"step\", \"interpolation\"}");
        onlyKeys(sampling, "sampling", {"step", "interpolation"});
        if (sampling.contains("step")) {
            s.step = number(sampling["step"], "sampling.step");
            if (s.step <= 0.0 || s.step > kMaxStep)
                fail("sampling.step", "expected a number > 0 and <= " + std::to_string(int(kMaxStep)));
        }
        if (sampling.contains("interpolation")) {
            const std::string name = string(sampling["interpolation"], "sampling.interpolation");
            s.interpolation = located("sampling.interpolation", [&] { return parseInterpolation(name); });
        }
    }

    if (j.contains("window")) {
        const json& w = j["window"];
        const char* msg = "expected [lo, hi], numbers with hi > lo";
        if (!w.is_array() || w.size() != 2) fail("window", msg);
        const glm::dvec2 lohi(number(w[0], "window[0]"), number(w[1], "window[1]"));
        if (!(lohi.y > lohi.x)) fail("window", msg);
        s.window = lohi;
    }

    if (j.contains("background")) {
        const json& b = j["background"];
        const char* msg = "expected [r, g, b], numbers in 0..1";
        if (!b.is_array() || b.size() != 3) fail("background", msg);
        for (int k = 0; k < 3; ++k) {
            if (!b[k].is_number()) fail("background", msg);
            const double c = b[k].get<double>();
            if (!(c >= 0.0 && c <= 1.0)) fail("background", msg);
            s.background[k] = float(c);
        }
    }

    if (j.contains("parameters")) {
        const json& params = j["parameters"];
        if (!params.is_object()) fail("parameters", "expected an object {\"name\": value}");
        for (const auto& item : params.items()) {
            const std::string key = "parameters." + item.key();
            if (item.value().is_boolean()) s.parameters[item.key()] = item.value().get<bool>() ? 1.0 : 0.0;
            else if (item.value().is_number() && std::isfinite(item.value().get<double>()))
                s.parameters[item.key()] = item.value().get<double>();
            else fail(key, "expected a number or true/false");
        }
    }

    if (j.contains("transfer_function")) {
        const json& tf = j["transfer_function"];
        if (tf.is_string()) {
            const std::string name = tf.get<std::string>();
            s.transferFunction = located("transfer_function", [&] {
                return TransferFunction::load(resolveDataPath(name, baseDir_));
            });
        } else {
            s.transferFunction = TransferFunction::fromJson(tf, where_, "transfer_function");
        }
    }
    return s;
}

using json_text::shortFloat;

}  // namespace

Scene Scene::fromJson(const json& j, const std::string& where, const std::string& baseDir) {
    return Parser(where, baseDir).parse(j);
}

Scene Scene::load(const std::string& path) {
    const json j = json_text::readJsonFile(path);
    return fromJson(j, path, std::filesystem::path(path).parent_path().string());
}

json Scene::toJson() const {
    json j;
    j["dataset"] = dataset;
    j["renderer"] = renderer;
    if (!camera.view.empty()) {
        j["camera"] = {{"view", camera.view}, {"zoom", camera.zoom}};
    } else {
        j["camera"] = {{"azimuth", camera.azimuth}, {"elevation", camera.elevation},
                       {"distance", camera.distance}, {"fov", camera.fov}, {"zoom", camera.zoom}};
    }
    j["projection"] = projectionName(camera.projection);
    j["size"] = {width, height};
    j["sampling"] = {{"step", step}, {"interpolation", interpolationName(interpolation)}};
    if (window) j["window"] = {window->x, window->y};
    j["background"] = {shortFloat(background.r), shortFloat(background.g), shortFloat(background.b)};
    j["parameters"] = json::object();
    for (const auto& [name, value] : parameters) j["parameters"][name] = value;
    if (transferFunction) j["transfer_function"] = transferFunction->toJson();
    return j;
}

}  // namespace voxlab
