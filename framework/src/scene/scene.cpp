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
    switch (i) {
        case Interpolation::Nearest: return "nearest";
        case Interpolation::Trilinear: return "trilinear";
        case Interpolation::Hardware: return "hardware";
    }
    return "?";
}

Interpolation parseInterpolation(const std::string& name) {
    for (Interpolation i : {Interpolation::Nearest, Interpolation::Trilinear, Interpolation::Hardware})
        if (name == interpolationName(i)) return i;
    throw Error("unknown interpolation '" + name + "' (expected nearest, trilinear or hardware)");
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
    glm::dvec3 vec3(const json& j, const std::string& key) const;
    ParameterValues parameters(const json& j, const std::string& key) const;
    TransferFunction transferFunction(const json& j, const std::string& key) const;
    RegionOfInterest roi(const json& j) const;
    CuttingPlane cuttingPlane(const json& j) const;

    std::string where_, baseDir_;
};

void Parser::camera(const json& j, CameraSpec* cam) const {
    if (!j.is_object())
        fail("camera", "expected an object: {\"view\": \"+z\"} or azimuth/elevation/distance/fov/zoom/pan");
    onlyKeys(j, "camera", {"view", "azimuth", "elevation", "distance", "fov", "zoom", "pan"});
    if (j.contains("view")) {
        for (const char* orbit : {"azimuth", "elevation", "distance", "fov"})
            if (j.contains(orbit))
                fail("camera", std::string("'view' cannot be combined with '") + orbit +
                                   "' (only with 'zoom' and 'pan')");
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
    if (j.contains("pan")) {
        // The look-at point's offset from the box centre, in bounding-sphere
        // radii along the image's right and down directions (camera.h).
        const json& pan = j["pan"];
        if (!pan.is_array() || pan.size() != 2) fail("camera.pan", "expected [x, y]");
        cam->pan = glm::dvec2(number(pan[0], "camera.pan[0]"), number(pan[1], "camera.pan[1]"));
    }
}

glm::dvec3 Parser::vec3(const json& j, const std::string& key) const {
    if (!j.is_array() || j.size() != 3) fail(key, "expected [x, y, z]");
    return {number(j[0], key + "[0]"), number(j[1], key + "[1]"), number(j[2], key + "[2]")};
}

ParameterValues Parser::parameters(const json& params, const std::string& key) const {
    if (!params.is_object()) fail(key, "expected an object {\"name\": value}");
    ParameterValues out;
    for (const auto& item : params.items()) {
        if (item.value().is_boolean()) out[item.key()] = item.value().get<bool>() ? 1.0 : 0.0;
        else if (item.value().is_number() && std::isfinite(item.value().get<double>()))
            out[item.key()] = item.value().get<double>();
        else fail(key + "." + item.key(), "expected a number or true/false");
    }
    return out;
}

TransferFunction Parser::transferFunction(const json& tf, const std::string& key) const {
    if (!tf.is_string()) return TransferFunction::fromJson(tf, where_, key);
    const std::string name = tf.get<std::string>();
    return located(key, [&] { return TransferFunction::load(resolveDataPath(name, baseDir_)); });
}

RegionOfInterest Parser::roi(const json& j) const {
    if (!j.is_object()) fail("roi", "expected an object {\"min\": [x,y,z], \"max\": [x,y,z]}");
    onlyKeys(j, "roi", {"min", "max"});
    if (!j.contains("min") || !j.contains("max")) fail("roi", "needs both \"min\" and \"max\"");
    RegionOfInterest r{vec3(j["min"], "roi.min"), vec3(j["max"], "roi.max")};
    for (int k = 0; k < 3; ++k)
        if (!(r.max[k] > r.min[k])) fail("roi", "max must be greater than min on every axis");
    return r;
}

CuttingPlane Parser::cuttingPlane(const json& j) const {
    if (!j.is_object()) fail("cutting_plane", "expected an object {\"point\", \"normal\", \"other_side\"}");
    onlyKeys(j, "cutting_plane", {"point", "normal", "other_side"});
    CuttingPlane c;
    if (j.contains("point")) c.point = vec3(j["point"], "cutting_plane.point");
    if (j.contains("normal")) c.normal = vec3(j["normal"], "cutting_plane.normal");
    if (glm::length(c.normal) <= 0.0) fail("cutting_plane.normal", "must not be zero");
    if (j.contains("other_side")) {
        const json& o = j["other_side"];
        const std::string key = "cutting_plane.other_side";
        if (!o.is_object()) fail(key, "expected an object {\"renderer\", \"transfer_function\", \"parameters\"}");
        onlyKeys(o, key, {"renderer", "transfer_function", "parameters"});
        if (o.contains("renderer")) c.otherRenderer = string(o["renderer"], key + ".renderer");
        if (o.contains("transfer_function"))
            c.otherTransferFunction = transferFunction(o["transfer_function"], key + ".transfer_function");
        if (o.contains("parameters")) c.otherParameters = parameters(o["parameters"], key + ".parameters");
    }
    return c;
}

Scene Parser::parse(const json& j) const {
    if (!j.is_object()) throw Error((where_.empty() ? "" : where_ + ": ") + "expected a JSON object");
    onlyKeys(j, "", {"dataset", "renderer", "camera", "projection", "size", "sampling", "window",
                     "background", "parameters", "transfer_function", "tf2d", "roi", "cutting_plane"});
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
        if (!sampling.is_object())
            fail("sampling", "expected an object {\"step\", \"interpolation\", \"skip_empty_space\"}");
        onlyKeys(sampling, "sampling", {"step", "interpolation", "skip_empty_space"});
        if (sampling.contains("step")) {
            s.step = number(sampling["step"], "sampling.step");
            if (s.step <= 0.0 || s.step > kMaxStep)
                fail("sampling.step", "expected a number > 0 and <= " + std::to_string(int(kMaxStep)));
        }
        if (sampling.contains("interpolation")) {
            const std::string name = string(sampling["interpolation"], "sampling.interpolation");
            s.interpolation = located("sampling.interpolation", [&] { return parseInterpolation(name); });
        }
        if (sampling.contains("skip_empty_space")) {
            if (!sampling["skip_empty_space"].is_boolean()) fail("sampling.skip_empty_space", "expected true or false");
            s.skipEmptySpace = sampling["skip_empty_space"].get<bool>();
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

    if (j.contains("parameters")) s.parameters = parameters(j["parameters"], "parameters");
    if (j.contains("transfer_function")) s.transferFunction = transferFunction(j["transfer_function"], "transfer_function");
    if (j.contains("tf2d")) {
        const json& t = j["tf2d"];
        if (t.is_string()) {
            const std::string name = t.get<std::string>();
            s.transferFunction2D =
                located("tf2d", [&] { return TransferFunction2D::load(resolveDataPath(name, baseDir_)); });
        } else {
            s.transferFunction2D = TransferFunction2D::fromJson(t, where_, "tf2d");
        }
    }
    if (j.contains("roi")) s.roi = roi(j["roi"]);
    if (j.contains("cutting_plane")) s.cuttingPlane = cuttingPlane(j["cutting_plane"]);
    return s;
}

using json_text::shortFloat;

}  // namespace

Scene Scene::fromJson(const json& j, const std::string& where, const std::string& baseDir) {
    return json_text::escapedErrors([&] { return Parser(where, baseDir).parse(j); });
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
    // A zero pan is left out, so that scenes without one read as before.
    if (camera.pan != glm::dvec2(0.0)) j["camera"]["pan"] = {camera.pan.x, camera.pan.y};
    j["projection"] = projectionName(camera.projection);
    j["size"] = {width, height};
    j["sampling"] = {{"step", step}, {"interpolation", interpolationName(interpolation)}};
    if (!skipEmptySpace) j["sampling"]["skip_empty_space"] = false;  // on unless said
    if (window) j["window"] = {window->x, window->y};
    j["background"] = {shortFloat(background.r), shortFloat(background.g), shortFloat(background.b)};
    j["parameters"] = json::object();
    for (const auto& [name, value] : parameters) j["parameters"][name] = value;
    if (transferFunction) j["transfer_function"] = transferFunction->toJson();
    if (transferFunction2D) j["tf2d"] = transferFunction2D->toJson();
    if (roi) j["roi"] = {{"min", {roi->min.x, roi->min.y, roi->min.z}}, {"max", {roi->max.x, roi->max.y, roi->max.z}}};
    if (cuttingPlane) {
        const CuttingPlane& c = *cuttingPlane;
        json cut = {{"normal", {c.normal.x, c.normal.y, c.normal.z}}};
        if (c.point) cut["point"] = {c.point->x, c.point->y, c.point->z};
        json other = {{"renderer", c.otherRenderer}, {"parameters", json::object()}};
        for (const auto& [name, value] : c.otherParameters) other["parameters"][name] = value;
        if (c.otherTransferFunction) other["transfer_function"] = c.otherTransferFunction->toJson();
        cut["other_side"] = other;
        j["cutting_plane"] = cut;
    }
    return j;
}

}  // namespace voxlab
