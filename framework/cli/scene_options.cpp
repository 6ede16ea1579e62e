// voxlab CLI: scene-building options shared by `render` and `view`. Flags
// override the scene file, key by key.
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "commands.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/volume.h"

namespace voxlab::cli {

std::vector<OptionSpec> sceneOptions() {
    return {
        {"dataset", "PATH|phantom:NAME[:N]", "volume file (.nrrd .nhdr .fld .dat), DICOM series folder or built-in phantom"},
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
        {"interpolation", "I", "nearest, trilinear (in the shader), hardware (GPU filtering), bspline or catmull-rom (cubic)"},
        {"skip-empty-space", "on|off", "leap over bricks that cannot change the image (default on)"},
        {"gpu-memory", "MIB", "texture memory the volume may take; a larger volume is drawn in bricks (default: the driver's)"},
        {"window", "LO,HI", "grey window in data units (default: the data's min,max)"},
        {kTransferFunctionName, "FILE", "1D transfer function (JSON control points)"},
        {"background", "R,G,B", "background colour, 0..1 each"},
        {"param", "NAME=VALUE", "a renderer parameter (repeatable)"},
        {kTransferFunction2DName, "FILE", "2D transfer function (JSON widgets), for renderers that classify by value and gradient"},
        {"roi", "X0,Y0,Z0,X1,Y1,Z1", "crop to this box, in voxel coordinates (the volume is 0..dims)"},
        {"cut-normal", "NX,NY,NZ", "cutting plane: the scene's renderer draws the side this points into"},
        {"cut-point", "X,Y,Z", "cutting plane: a point on it, voxel coordinates (default: the centre)"},
        {"cut-renderer", "ID|none", "cutting plane: renderer of the other side (default: none, invisible)"},
        {"cut-tf", "FILE", "cutting plane: transfer function of the other side"},
        {"cut-param", "NAME=VALUE", "cutting plane: a parameter of the other side's renderer (repeatable)"},
        {"clip-plane", "X,Y,Z,NX,NY,NZ", "keep the side of the plane through voxel point X,Y,Z that NX,NY,NZ points into (repeatable, up to 6)"},
        {"labels", "FILE", "label map on the dataset's grid: each label shown by its own transfer function (compositing)"},
        {"label-tf", "LABEL=FILE", "labels: the transfer function of one label (repeatable)"},
        {"hide-label", "LABEL", "labels: hide one label (repeatable)"},
        {"label-sampling", "nearest|masks", "labels: the voxel's label, or each label's mask interpolated (smooth borders)"},
        {"label-distance", "LABEL=FILE", "labels: colour the other labels by their distance to LABEL through this transfer function (world units)"},
        {"fuse", "PATH", "a second volume over the same box, fused with the first (compositing)"},
        {"fusion-mode", "MODE", "checkerboard, split, color_opacity or sum (default)"},
        {"fusion-tf", "FILE", "the second volume's transfer function"},
        {"fusion-window", "LO,HI", "the second volume's window (its default ramp)"},
        volumeCapOption(),
    };
}

OptionSpec volumeCapOption() {
    return {"max-volume-mib", "MIB",
            "refuse volumes with more voxel data (default " + std::to_string(kDefaultVolumeCapMiB) + ", or $" +
                kVolumeCapVariable + ")"};
}

void applyVolumeCapOption(const Args& args) {
    const auto value = args.get("max-volume-mib");
    if (!value) return;
    const std::uint64_t mib = parseVolumeCapMiB(*value, "option --max-volume-mib");
    // Set through the environment, the one place the cap is read (volume.h):
    // this process's loaders and any worker process it starts see the same.
    ::setenv(kVolumeCapVariable, std::to_string(mib).c_str(), 1);
}

Volume loadDatasetArgument(const Args& args) {
    applyVolumeCapOption(args);
    return loadVolume(resolveDataPath(args.positionals().at(0)));
}

std::string defaultScenePath() { return projectRoot() + "/datasets/scenes/default.json"; }

namespace {

int parseLabel(const std::string& text, const std::string& option) {
    const double v = parseNumber(text, "--" + option);
    if (!(v >= 0.0 && v <= kMaxLabel && v == std::floor(v)))
        throw Error("option --" + option + ": expected a label, a whole number in 0.." + std::to_string(kMaxLabel) +
                    ", got '" + text + "'");
    return int(v);
}

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

void parseParam(const std::string& text, const std::string& option, ParameterValues* values) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
        throw Error("option --" + option + ": expected NAME=VALUE, got '" + text + "'");
    const std::string name = text.substr(0, eq), value = text.substr(eq + 1);
    if (value == "true" || value == "on") (*values)[name] = 1.0;
    else if (value == "false" || value == "off") (*values)[name] = 0.0;
    else (*values)[name] = parseNumber(value, "--" + option + " " + name);
}

void parseCuttingPlane(const Args& args, Scene* scene) {
    const bool any = args.has("cut-normal") || args.has("cut-point") || args.has("cut-renderer") ||
                     args.has("cut-tf") || !args.getAll("cut-param").empty();
    if (!any) return;
    if (!scene->cuttingPlane && !args.has("cut-normal"))
        throw Error("option --cut-*: the cutting plane needs --cut-normal (or a scene with a cutting plane)");
    CuttingPlane& cut = scene->cuttingPlane ? *scene->cuttingPlane : scene->cuttingPlane.emplace();
    if (auto v = args.get("cut-normal")) {
        const auto n = parseNumberList(*v, "--cut-normal", 3);
        cut.normal = glm::dvec3(n[0], n[1], n[2]);
        if (glm::length(cut.normal) <= 0.0) throw Error("option --cut-normal: must not be zero");
    }
    if (auto v = args.get("cut-point")) {
        const auto p = parseNumberList(*v, "--cut-point", 3);
        cut.point = glm::dvec3(p[0], p[1], p[2]);
    }
    if (auto v = args.get("cut-renderer")) cut.otherRenderer = *v;
    if (auto v = args.get("cut-tf")) cut.otherTransferFunction = TransferFunction::load(resolveDataPath(*v));
    for (const std::string& p : args.getAll("cut-param")) parseParam(p, "cut-param", &cut.otherParameters);
}

// "LABEL=FILE": a label and a transfer function.
std::pair<int, TransferFunction> labelFunction(const std::string& text, const std::string& option) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos) throw Error("option --" + option + ": expected LABEL=FILE, got '" + text + "'");
    return {parseLabel(text.substr(0, eq), option), TransferFunction::load(resolveDataPath(text.substr(eq + 1)))};
}

LabelClass& labelClass(LabelMap* map, int label) {
    for (LabelClass& c : map->classes)
        if (c.label == label) return c;
    if (map->classes.size() >= kMaxLabelClasses)
        throw Error("labels: at most " + std::to_string(kMaxLabelClasses) + " classes");
    map->classes.push_back(LabelClass{label, "", std::nullopt, true});
    return map->classes.back();
}

void parseLabels(const Args& args, Scene* scene) {
    if (auto v = args.get("labels")) {
        if (!scene->labels) scene->labels.emplace();
        scene->labels->volume = resolveDataPath(*v);
    }
    const bool any = args.has("label-tf") || args.has("hide-label") || args.has("label-sampling") ||
                     args.has("label-distance");
    if (!any) return;
    if (!scene->labels) throw Error("option --label-*: needs a label map (--labels FILE, or a scene with \"labels\")");
    LabelMap& map = *scene->labels;
    for (const std::string& t : args.getAll("label-tf")) {
        auto [label, function] = labelFunction(t, "label-tf");
        labelClass(&map, label).transferFunction = function;
    }
    for (const std::string& t : args.getAll("hide-label")) labelClass(&map, parseLabel(t, "hide-label")).visible = false;
    if (auto v = args.get("label-sampling")) {
        if (*v != "nearest" && *v != "masks")
            throw Error("option --label-sampling: expected nearest or masks, got '" + *v + "'");
        map.sampling = *v == "masks" ? LabelSampling::Masks : LabelSampling::Nearest;
    }
    if (auto v = args.get("label-distance")) {
        auto [label, function] = labelFunction(*v, "label-distance");
        if (function.empty()) throw Error("option --label-distance: the transfer function has no points");
        map.distance = LabelDistance{label, function, {}};
    }
}

void parseFusion(const Args& args, Scene* scene) {
    if (auto v = args.get("fuse")) {
        if (!scene->fusion) scene->fusion.emplace();
        scene->fusion->dataset = resolveDataPath(*v);
    }
    if (!args.has("fusion-mode") && !args.has("fusion-tf") && !args.has("fusion-window")) return;
    if (!scene->fusion) throw Error("option --fusion-*: needs a second volume (--fuse PATH, or a scene with \"fusion\")");
    Fusion& f = *scene->fusion;
    if (auto v = args.get("fusion-mode")) f.mode = parseFusionMode(*v);
    if (auto v = args.get("fusion-tf")) f.transferFunction = TransferFunction::load(resolveDataPath(*v));
    if (auto v = args.get("fusion-window")) {
        const auto w = parseNumberList(*v, "--fusion-window", 2);
        if (!(w[1] > w[0])) throw Error("option --fusion-window: HI must be greater than LO");
        f.window = glm::dvec2(w[0], w[1]);
    }
}

void parseClipPlanes(const Args& args, Scene* scene) {
    const std::vector<std::string> planes = args.getAll("clip-plane");
    if (planes.empty()) return;
    scene->clipPlanes.clear();  // the command line's planes replace the scene's
    if (planes.size() > kMaxClipPlanes)
        throw Error("option --clip-plane: at most " + std::to_string(kMaxClipPlanes) + " planes");
    for (const std::string& text : planes) {
        const auto v = parseNumberList(text, "--clip-plane", 6);
        const ClipPlane plane{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
        if (glm::length(plane.normal) <= 0.0) throw Error("option --clip-plane: the normal must not be zero");
        scene->clipPlanes.push_back(plane);
    }
}

}  // namespace

Scene sceneFromArgs(const Args& args, const std::string& command, const Scene* base) {
    applyVolumeCapOption(args);  // before anything loads a volume
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
    if (auto v = args.get("skip-empty-space")) {
        if (*v != "on" && *v != "off") throw Error("option --skip-empty-space: expected on or off, got '" + *v + "'");
        scene.skipEmptySpace = *v == "on";
    }
    if (auto v = args.get("gpu-memory")) {
        scene.gpuMemoryMiB = parseNumber(*v, "--gpu-memory");
        if (!(*scene.gpuMemoryMiB >= 1.0 && *scene.gpuMemoryMiB <= kMaxGpuMemoryMiB))
            throw Error("option --gpu-memory: must be in 1.." + std::to_string(long(kMaxGpuMemoryMiB)) + " MiB");
    }
    if (auto v = args.get("window")) {
        const auto w = parseNumberList(*v, "--window", 2);
        if (!(w[1] > w[0])) throw Error("option --window: HI must be greater than LO");
        scene.window = glm::dvec2(w[0], w[1]);
    }
    if (auto v = args.get(kTransferFunctionName)) scene.transferFunction = TransferFunction::load(resolveDataPath(*v));
    if (auto v = args.get("background")) {
        const auto c = parseNumberList(*v, "--background", 3);
        scene.background = glm::vec3(c[0], c[1], c[2]);
    }
    for (const std::string& p : args.getAll("param")) parseParam(p, "param", &scene.parameters);
    if (auto v = args.get(kTransferFunction2DName)) scene.transferFunction2D = TransferFunction2D::load(resolveDataPath(*v));
    if (auto v = args.get("roi")) {
        const auto r = parseNumberList(*v, "--roi", 6);
        scene.roi = RegionOfInterest{{r[0], r[1], r[2]}, {r[3], r[4], r[5]}};
        for (int k = 0; k < 3; ++k)
            if (!(r[3 + k] > r[k])) throw Error("option --roi: X1,Y1,Z1 must be greater than X0,Y0,Z0");
    }
    parseCuttingPlane(args, &scene);
    parseClipPlanes(args, &scene);
    parseLabels(args, &scene);
    parseFusion(args, &scene);
    if (scene.camera.fov <= 0.0 || scene.camera.fov >= 180.0) throw Error(command + ": --fov must be in (0, 180)");
    if (scene.camera.zoom <= 0.0) throw Error(command + ": --zoom must be positive");
    return scene;
}

}  // namespace voxlab::cli
