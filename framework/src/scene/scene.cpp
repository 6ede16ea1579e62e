// voxlab: scene files. The schema is in scene.h; every error names the file
// and the key path ("scene.json: camera.azimut: unknown key").
#include "voxlab/scene.h"

#include <algorithm>
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
#include "voxlab/scene_section.h"

namespace voxlab {

const char* interpolationName(Interpolation i) {
    switch (i) {
        case Interpolation::Nearest: return "nearest";
        case Interpolation::Trilinear: return "trilinear";
        case Interpolation::Hardware: return "hardware";
        case Interpolation::BSpline: return "bspline";
        case Interpolation::CatmullRom: return "catmull-rom";
    }
    return "?";
}

Interpolation parseInterpolation(const std::string& name) {
    for (Interpolation i : {Interpolation::Nearest, Interpolation::Trilinear, Interpolation::Hardware,
                            Interpolation::BSpline, Interpolation::CatmullRom})
        if (name == interpolationName(i)) return i;
    throw Error("unknown interpolation '" + name +
                "' (expected nearest, trilinear, hardware, bspline or catmull-rom)");
}

const char* fusionModeName(FusionMode mode) {
    switch (mode) {
        case FusionMode::Checkerboard: return "checkerboard";
        case FusionMode::Split: return "split";
        case FusionMode::ColorOpacity: return "color_opacity";
        case FusionMode::Sum: return "sum";
    }
    return "?";
}

FusionMode parseFusionMode(const std::string& name) {
    for (FusionMode m : {FusionMode::Checkerboard, FusionMode::Split, FusionMode::ColorOpacity, FusionMode::Sum})
        if (name == fusionModeName(m)) return m;
    throw Error("unknown fusion mode '" + name + "' (expected checkerboard, split, color_opacity or sum)");
}

const LabelClass* LabelMap::find(int label) const {
    for (const LabelClass& c : classes)
        if (c.label == label) return &c;
    return nullptr;
}

using json = nlohmann::json;

void SceneReader::fail(const std::string& key, const std::string& message) const {
    throw Error((where_.empty() ? "" : where_ + ": ") + key + ": " + message);
}

namespace {

// Fails on the first key of `obj` (at `path`) for which known(key) is false.
template <class Known>
void refuseUnknownKeys(const SceneReader& reader, const json& obj, const std::string& path, Known known) {
    for (const auto& item : obj.items())
        if (!known(item.key())) reader.fail(path.empty() ? item.key() : path + "." + item.key(), "unknown key");
}

bool among(const std::string& key, std::initializer_list<const char*> names) {
    return std::any_of(names.begin(), names.end(), [&](const char* name) { return key == name; });
}

}  // namespace

void SceneReader::onlyKeys(const json& obj, const std::string& path,
                           std::initializer_list<const char*> allowed) const {
    refuseUnknownKeys(*this, obj, path, [&](const std::string& key) { return among(key, allowed); });
}

double SceneReader::number(const json& j, const std::string& key) const {
    if (!j.is_number() || !std::isfinite(j.get<double>())) fail(key, "expected a number");
    return j.get<double>();
}

std::string SceneReader::string(const json& j, const std::string& key) const {
    if (!j.is_string()) fail(key, "expected a string");
    return j.get<std::string>();
}

glm::dvec3 SceneReader::vec3(const json& j, const std::string& key) const {
    if (!j.is_array() || j.size() != 3) fail(key, "expected [x, y, z]");
    return {number(j[0], key + "[0]"), number(j[1], key + "[1]"), number(j[2], key + "[2]")};
}

ParameterValues SceneReader::parameters(const json& params, const std::string& key) const {
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

TransferFunction SceneReader::transferFunction(const json& tf, const std::string& key) const {
    if (!tf.is_string()) return TransferFunction::fromJson(tf, where_, key);
    const std::string name = tf.get<std::string>();
    return located(key, [&] { return TransferFunction::load(resolveDataPath(name, baseDir_)); });
}

std::string SceneReader::dataPath(const json& j, const std::string& key) const {
    const std::string name = string(j, key);
    return located(key, [&] { return resolveDataPath(name, baseDir_); });
}

namespace {

// Reads one scene; `where` is the file name used in every message. The
// sections that stages bring are read by theirs (voxlab/scene_section.h).
class Parser : public SceneReader {
public:
    using SceneReader::SceneReader;

    Scene parse(const json& j) const;

private:
    void topLevelKeys(const json& j) const;
    void camera(const json& j, CameraSpec* cam) const;
    glm::dvec2 window(const json& j, const std::string& key) const;
    RegionOfInterest roi(const json& j) const;
    void sampling(const json& j, Scene* s) const;
    int label(const json& j, const std::string& key) const;
    LabelClass labelClass(const json& j, const std::string& key) const;
    LabelDistance labelDistance(const json& j) const;
    LabelMap labels(const json& j) const;
    Fusion fusion(const json& j) const;
    std::vector<ClipPlane> clipPlanes(const json& j) const;
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

glm::dvec2 Parser::window(const json& w, const std::string& key) const {
    const char* msg = "expected [lo, hi], numbers with hi > lo";
    if (!w.is_array() || w.size() != 2) fail(key, msg);
    const glm::dvec2 lohi(number(w[0], key + "[0]"), number(w[1], key + "[1]"));
    if (!(lohi.y > lohi.x)) fail(key, msg);
    return lohi;
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

void Parser::sampling(const json& sampling, Scene* s) const {
    if (!sampling.is_object())
        fail("sampling", "expected an object {\"step\", \"interpolation\", \"skip_empty_space\"}");
    onlyKeys(sampling, "sampling", {"step", "interpolation", "skip_empty_space"});
    if (sampling.contains("step")) {
        s->step = number(sampling["step"], "sampling.step");
        if (s->step <= 0.0 || s->step > kMaxStep)
            fail("sampling.step", "expected a number > 0 and <= " + std::to_string(int(kMaxStep)));
    }
    if (sampling.contains("interpolation")) {
        const std::string name = string(sampling["interpolation"], "sampling.interpolation");
        s->interpolation = located("sampling.interpolation", [&] { return parseInterpolation(name); });
    }
    if (sampling.contains("skip_empty_space")) {
        if (!sampling["skip_empty_space"].is_boolean()) fail("sampling.skip_empty_space", "expected true or false");
        s->skipEmptySpace = sampling["skip_empty_space"].get<bool>();
    }
}

int Parser::label(const json& j, const std::string& key) const {
    if (!j.is_number_integer() || j.get<long long>() < 0 || j.get<long long>() > kMaxLabel)
        fail(key, "expected a label, a whole number in 0.." + std::to_string(kMaxLabel));
    return j.get<int>();
}

LabelClass Parser::labelClass(const json& j, const std::string& key) const {
    if (!j.is_object()) fail(key, "expected an object {\"label\", \"name\", \"transfer_function\", \"visible\"}");
    onlyKeys(j, key, {"label", "name", "transfer_function", "visible"});
    if (!j.contains("label")) fail(key + ".label", "missing (required)");
    LabelClass c;
    c.label = label(j["label"], key + ".label");
    if (j.contains("name")) c.name = string(j["name"], key + ".name");
    if (j.contains("transfer_function")) {
        c.transferFunction = transferFunction(j["transfer_function"], key + ".transfer_function");
        if (c.transferFunction->empty()) fail(key + ".transfer_function", "needs at least one point");
    }
    if (j.contains("visible")) {
        if (!j["visible"].is_boolean()) fail(key + ".visible", "expected true or false");
        c.visible = j["visible"].get<bool>();
    }
    return c;
}

LabelDistance Parser::labelDistance(const json& j) const {
    const std::string key = "labels.distance";
    if (!j.is_object()) fail(key, "expected an object {\"to\", \"transfer_function\", \"apply_to\"}");
    onlyKeys(j, key, {"to", "transfer_function", "apply_to"});
    for (const char* required : {"to", "transfer_function"})
        if (!j.contains(required)) fail(key + "." + required, "missing (required)");
    LabelDistance d;
    d.to = label(j["to"], key + ".to");
    d.transferFunction = transferFunction(j["transfer_function"], key + ".transfer_function");
    if (d.transferFunction.empty()) fail(key + ".transfer_function", "needs at least one point");
    if (j.contains("apply_to")) {
        if (!j["apply_to"].is_array()) fail(key + ".apply_to", "expected an array of labels");
        for (std::size_t i = 0; i < j["apply_to"].size(); ++i)
            d.applyTo.push_back(label(j["apply_to"][i], key + ".apply_to[" + std::to_string(i) + "]"));
    }
    return d;
}

LabelMap Parser::labels(const json& j) const {
    if (j.is_string()) return LabelMap{dataPath(j, "labels"), LabelSampling::Nearest, {}, std::nullopt};
    if (!j.is_object()) fail("labels", "expected a label volume's path or an object {\"volume\", \"classes\", ...}");
    onlyKeys(j, "labels", {"volume", "sampling", "classes", "distance"});
    if (!j.contains("volume")) fail("labels.volume", "missing (required)");
    LabelMap m;
    m.volume = dataPath(j["volume"], "labels.volume");
    if (j.contains("sampling")) {
        const std::string how = string(j["sampling"], "labels.sampling");
        if (how == "nearest") m.sampling = LabelSampling::Nearest;
        else if (how == "masks") m.sampling = LabelSampling::Masks;
        else fail("labels.sampling", "unknown sampling '" + how + "' (expected nearest or masks)");
    }
    if (j.contains("classes")) {
        const json& classes = j["classes"];
        if (!classes.is_array()) fail("labels.classes", "expected an array of classes");
        if (classes.size() > kMaxLabelClasses)
            fail("labels.classes", "at most " + std::to_string(kMaxLabelClasses) + " classes");
        for (std::size_t i = 0; i < classes.size(); ++i) {
            const std::string key = "labels.classes[" + std::to_string(i) + "]";
            LabelClass c = labelClass(classes[i], key);
            if (m.find(c.label)) fail(key + ".label", "label " + std::to_string(c.label) + " has a class already");
            m.classes.push_back(std::move(c));
        }
    }
    if (j.contains("distance")) m.distance = labelDistance(j["distance"]);
    return m;
}

Fusion Parser::fusion(const json& j) const {
    if (!j.is_object()) fail("fusion", "expected an object {\"dataset\", \"mode\", ...}");
    onlyKeys(j, "fusion", {"dataset", "mode", "window", "transfer_function", "checker_size", "split"});
    if (!j.contains("dataset")) fail("fusion.dataset", "missing (required)");
    Fusion f;
    f.dataset = dataPath(j["dataset"], "fusion.dataset");
    if (j.contains("mode")) {
        const std::string mode = string(j["mode"], "fusion.mode");
        f.mode = located("fusion.mode", [&] { return parseFusionMode(mode); });
    }
    if (j.contains("window")) f.window = window(j["window"], "fusion.window");
    if (j.contains("transfer_function"))
        f.transferFunction = transferFunction(j["transfer_function"], "fusion.transfer_function");
    if (j.contains("checker_size")) {
        f.checkerSize = number(j["checker_size"], "fusion.checker_size");
        if (!(f.checkerSize >= 1.0 && f.checkerSize <= 4096.0))
            fail("fusion.checker_size", "expected a number of voxels in 1..4096");
    }
    if (j.contains("split")) {
        const json& split = j["split"];
        if (!split.is_object()) fail("fusion.split", "expected an object {\"point\", \"normal\"}");
        onlyKeys(split, "fusion.split", {"point", "normal"});
        if (split.contains("point")) f.splitPoint = vec3(split["point"], "fusion.split.point");
        if (split.contains("normal")) f.splitNormal = vec3(split["normal"], "fusion.split.normal");
        if (glm::length(f.splitNormal) <= 0.0) fail("fusion.split.normal", "must not be zero");
    }
    return f;
}

std::vector<ClipPlane> Parser::clipPlanes(const json& j) const {
    if (!j.is_array()) fail("clip_planes", "expected an array of planes {\"point\", \"normal\"}");
    if (j.size() > kMaxClipPlanes) fail("clip_planes", "at most " + std::to_string(kMaxClipPlanes) + " planes");
    std::vector<ClipPlane> planes;
    for (std::size_t i = 0; i < j.size(); ++i) {
        const std::string key = "clip_planes[" + std::to_string(i) + "]";
        if (!j[i].is_object()) fail(key, "expected an object {\"point\", \"normal\"}");
        onlyKeys(j[i], key, {"point", "normal"});
        for (const char* required : {"point", "normal"})
            if (!j[i].contains(required)) fail(key + "." + required, "missing (required)");
        ClipPlane p{vec3(j[i]["point"], key + ".point"), vec3(j[i]["normal"], key + ".normal")};
        if (glm::length(p.normal) <= 0.0) fail(key + ".normal", "must not be zero");
        planes.push_back(p);
    }
    return planes;
}

void Parser::topLevelKeys(const json& j) const {
    if (!j.is_object()) throw Error((where().empty() ? "" : where() + ": ") + "expected a JSON object");
    const std::vector<SceneSection>& sections = stageSceneSections();
    refuseUnknownKeys(*this, j, "", [&](const std::string& key) {
        return among(key, {"dataset", "renderer", "camera", "projection", "size", "sampling", "window", "background",
                           "parameters", "transfer_function", "roi", "labels", "fusion", "clip_planes", "gpu_memory"}) ||
               std::any_of(sections.begin(), sections.end(), [&](const SceneSection& s) { return key == s.key; });
    });
}

Scene Parser::parse(const json& j) const {
    topLevelKeys(j);
    Scene s;

    if (!j.contains("dataset")) fail("dataset", "missing (required)");
    const std::string dataset = string(j["dataset"], "dataset");
    s.dataset = located("dataset", [&] { return resolveDataPath(dataset, baseDir()); });

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

    if (j.contains("sampling")) sampling(j["sampling"], &s);

    if (j.contains("window")) s.window = window(j["window"], "window");
    if (j.contains("gpu_memory")) {
        const json& m = j["gpu_memory"];
        if (!m.is_number() || !(m.get<double>() >= 1.0 && m.get<double>() <= kMaxGpuMemoryMiB))
            fail("gpu_memory", "expected a number of MiB in 1.." + std::to_string(long(kMaxGpuMemoryMiB)));
        s.gpuMemoryMiB = m.get<double>();
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
    if (j.contains("roi")) s.roi = roi(j["roi"]);
    if (j.contains("labels")) s.labels = labels(j["labels"]);
    if (j.contains("fusion")) s.fusion = fusion(j["fusion"]);
    if (j.contains("clip_planes")) s.clipPlanes = clipPlanes(j["clip_planes"]);
    for (const SceneSection& section : stageSceneSections())
        if (j.contains(section.key)) section.read(*this, j[section.key], s);
    return s;
}

using json_text::shortFloat;

json vec3Json(glm::dvec3 v) { return {v.x, v.y, v.z}; }

json labelsJson(const LabelMap& m) {
    json j = {{"volume", m.volume}, {"sampling", m.sampling == LabelSampling::Masks ? "masks" : "nearest"}};
    j["classes"] = json::array();
    for (const LabelClass& c : m.classes) {
        json cj = {{"label", c.label}, {"visible", c.visible}};
        if (!c.name.empty()) cj["name"] = c.name;
        if (c.transferFunction) cj["transfer_function"] = c.transferFunction->toJson();
        j["classes"].push_back(cj);
    }
    if (m.distance) {
        j["distance"] = {{"to", m.distance->to}, {"transfer_function", m.distance->transferFunction.toJson()}};
        if (!m.distance->applyTo.empty()) j["distance"]["apply_to"] = m.distance->applyTo;
    }
    return j;
}

json fusionJson(const Fusion& f) {
    json j = {{"dataset", f.dataset}, {"mode", fusionModeName(f.mode)}, {"checker_size", f.checkerSize}};
    if (f.window) j["window"] = {f.window->x, f.window->y};
    if (f.transferFunction) j["transfer_function"] = f.transferFunction->toJson();
    j["split"] = {{"normal", vec3Json(f.splitNormal)}};
    if (f.splitPoint) j["split"]["point"] = vec3Json(*f.splitPoint);
    return j;
}

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
    if (gpuMemoryMiB) j["gpu_memory"] = *gpuMemoryMiB;
    j["background"] = {shortFloat(background.r), shortFloat(background.g), shortFloat(background.b)};
    j["parameters"] = json::object();
    for (const auto& [name, value] : parameters) j["parameters"][name] = value;
    if (transferFunction) j["transfer_function"] = transferFunction->toJson();
    if (roi) j["roi"] = {{"min", {roi->min.x, roi->min.y, roi->min.z}}, {"max", {roi->max.x, roi->max.y, roi->max.z}}};
    if (labels) j["labels"] = labelsJson(*labels);
    if (fusion) j["fusion"] = fusionJson(*fusion);
    if (!clipPlanes.empty()) {
        j["clip_planes"] = json::array();
        for (const ClipPlane& p : clipPlanes) j["clip_planes"].push_back({{"point", vec3Json(p.point)}, {"normal", vec3Json(p.normal)}});
    }
    for (const SceneSection& section : stageSceneSections()) section.write(*this, j);
    return j;
}

}  // namespace voxlab
