// voxlab CLI: scene-building options shared by `render` and `view`. Flags
// override the scene file, key by key.
#include <sstream>

#include "commands.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"

namespace voxlab::cli {

std::vector<OptionSpec> sceneOptions() {
    return {
        {"dataset", "PATH|phantom:NAME[:N]", "volume file (.nrrd .nhdr .fld .dat) or built-in phantom"},
        {"renderer", "ID", "renderer id (see voxlab list)"},
        {"view", "AXIS", "axis view: +x -x +y -y +z -z (rays travel along it)"},
        {"azimuth", "DEG", "orbit camera azimuth (0 = +z view, 90 = +x view)"},
        {"elevation", "DEG", "orbit camera elevation (positive looks down from above)"},
        {"distance", "R", "orbit distance in bounding-sphere radii (perspective)"},
        {"fov", "DEG", "vertical field of view (perspective)"},
        {"zoom", "Z", "magnification (1 fits the volume)"},
        {"projection", "P", "orthographic or perspective"},
        {"size", "WxH", "image size in pixels"},
        {"step", "S", "sample spacing along rays, in units of the smallest voxel spacing"},
        {"interpolation", "I", "nearest or trilinear"},
        {"window", "LO,HI", "grey window in data units (default: the data's min,max)"},
        {"tf", "FILE", "1D transfer function (JSON control points)"},
        {"background", "R,G,B", "background colour, 0..1 each"},
        {"param", "NAME=VALUE", "a renderer parameter (repeatable)"},
    };
}

std::string defaultScenePath() { return projectRoot() + "/datasets/scenes/default.json"; }

namespace {

void parseSize(const std::string& text, Scene* scene) {
    const std::size_t x = text.find('x');
    if (x == std::string::npos) throw Error("option --size: expected WxH, got '" + text + "'");
    scene->width = parseInt(text.substr(0, x), "--size");
    scene->height = parseInt(text.substr(x + 1), "--size");
    if (scene->width < 1 || scene->height < 1 || scene->width > kMaxImageSize || scene->height > kMaxImageSize) {
        const std::string max = std::to_string(kMaxImageSize);
        throw Error("option --size: " + text + " is outside 1x1.." + max + "x" + max);
    }
}

void parseParam(const std::string& text, Scene* scene) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0) throw Error("option --param: expected NAME=VALUE, got '" + text + "'");
    const std::string name = text.substr(0, eq), value = text.substr(eq + 1);
    if (value == "true" || value == "on") scene->parameters[name] = 1.0;
    else if (value == "false" || value == "off") scene->parameters[name] = 0.0;
    else scene->parameters[name] = parseNumber(value, "--param " + name);
}

}  // namespace

Scene sceneFromArgs(const Args& args, const std::string& command, const Scene* base) {
    Scene scene;
    const auto& pos = args.positionals();
    if (pos.size() > 1) throw Error(command + ": expected at most one scene file, got '" + pos[1] + "' too");
    if (base) {
        scene = *base;
    } else if (!pos.empty()) {
        scene = Scene::load(pos[0]);
    } else if (!args.has("dataset")) {
        throw Error(command + ": no dataset: give a scene file or --dataset (see voxlab " + command + " --help)");
    }
    if (auto v = args.get("dataset")) scene.dataset = resolveDataPath(*v);
    if (auto v = args.get("renderer")) scene.renderer = *v;

    const bool orbit = args.has("azimuth") || args.has("elevation");
    if (auto v = args.get("view")) {
        if (orbit) throw Error(command + ": --view and --azimuth/--elevation exclude each other");
        if (!isAxisView(*v)) throw Error("option --view: unknown view '" + *v + "' (expected +x -x +y -y +z -z)");
        scene.camera.view = *v;
        scene.camera.projection = Projection::Orthographic;  // unless --projection says otherwise
    }
    if (orbit) scene.camera.view.clear();
    if (auto v = args.get("azimuth")) scene.camera.azimuth = parseNumber(*v, "--azimuth");
    if (auto v = args.get("elevation")) scene.camera.elevation = parseNumber(*v, "--elevation");
    if (auto v = args.get("distance")) scene.camera.distance = parseNumber(*v, "--distance");
    if (auto v = args.get("fov")) scene.camera.fov = parseNumber(*v, "--fov");
    if (auto v = args.get("zoom")) scene.camera.zoom = parseNumber(*v, "--zoom");
    if (auto v = args.get("projection")) scene.camera.projection = parseProjection(*v);
    if (auto v = args.get("size")) parseSize(*v, &scene);
    if (auto v = args.get("step")) {
        scene.step = parseNumber(*v, "--step");
        if (!(scene.step > 0.0 && scene.step <= kMaxStep))
            throw Error("option --step: must be in (0, " + std::to_string(int(kMaxStep)) + "]");
    }
    if (auto v = args.get("interpolation")) scene.interpolation = parseInterpolation(*v);
    if (auto v = args.get("window")) {
        const auto w = parseNumberList(*v, "--window", 2);
        if (!(w[1] > w[0])) throw Error("option --window: HI must be greater than LO");
        scene.window = glm::dvec2(w[0], w[1]);
    }
    if (auto v = args.get("tf")) scene.transferFunction = TransferFunction::load(resolveDataPath(*v));
    if (auto v = args.get("background")) {
        const auto c = parseNumberList(*v, "--background", 3);
        scene.background = glm::vec3(c[0], c[1], c[2]);
    }
    for (const std::string& p : args.getAll("param")) parseParam(p, &scene);
    if (scene.camera.fov <= 0.0 || scene.camera.fov >= 180.0) throw Error(command + ": --fov must be in (0, 180)");
    if (scene.camera.zoom <= 0.0) throw Error(command + ": --zoom must be positive");
    return scene;
}

}  // namespace voxlab::cli
