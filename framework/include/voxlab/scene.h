// voxlab: scene files (JSON). A scene says what to render and how.
//
//   {
//     "dataset": "bonsai.nrrd",              // path, or "phantom:sphere:64"
//     "renderer": "mip",                     // see `voxlab list`
//     "camera": {"view": "+z"},              // or {"azimuth": 30, "elevation": 20,
//                                            //     "distance": 2.6, "fov": 30, "zoom": 1}
//     "projection": "orthographic",          // or "perspective"
//     "size": [256, 256],                    // image width, height in pixels
//     "sampling": {"step": 0.5, "interpolation": "trilinear"},
//     "window": [0, 255],                    // grey window in data units
//     "background": [0, 0, 0],
//     "parameters": {"offset": 0},           // the renderer's own, see `voxlab list`
//     "transfer_function": [ {"value": 40, "color": [1,1,1], "alpha": 0}, ... ]
//                                            // or a path to such a JSON file
//   }
//
// Every key is optional except "dataset". Unknown keys and wrong types are
// errors that name the key: "scene.json: sampling.step: expected a number".
// Relative paths inside a scene are resolved against the scene file's folder
// first, then the dataset search path (see resolveDataPath).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "voxlab/camera.h"
#include "voxlab/transfer_function.h"

namespace voxlab {

enum class Interpolation { Nearest, Trilinear };
const char* interpolationName(Interpolation i);
Interpolation parseInterpolation(const std::string& name);  // throws voxlab::Error

// A renderer parameter's value as written in a scene or on the command
// line; the renderer's declared ParameterSpec checks and converts it.
using ParameterValues = std::map<std::string, double>;

// Limits every way of writing a scene (JSON, command line, viewer) obeys.
constexpr int kMaxImageSize = 8192;  // pixels, per side
constexpr double kMaxStep = 64.0;    // in smallest spacings; steps are in (0, kMaxStep]

struct Scene {
    std::string dataset;          // resolved path or phantom spec
    std::string renderer = "mip";
    CameraSpec camera;
    int width = 256;
    int height = 256;
    double step = 0.5;            // in units of the smallest voxel spacing
    Interpolation interpolation = Interpolation::Trilinear;
    std::optional<glm::dvec2> window;  // default: the dataset's min..max
    glm::vec3 background{0.0f};
    ParameterValues parameters;
    std::optional<TransferFunction> transferFunction;

    // Parses a scene; `where` prefixes error messages (usually the path),
    // `baseDir` resolves relative paths.
    static Scene fromJson(const nlohmann::json& j, const std::string& where,
                          const std::string& baseDir);
    static Scene load(const std::string& path);
    nlohmann::json toJson() const;
};

// Finds a data file: as given (absolute, or relative to the working
// directory), then relative to `baseDir` when given, then in each folder of
// the dataset search path: $VOXLAB_DATA_PATH (colon-separated) and the
// project's datasets/ folder. Phantom specs are returned unchanged. Throws
// voxlab::Error("NAME: no such file (searched: ...)") when nothing matches.
// The project's datasets/ folder is $VOXLAB_ROOT/datasets when VOXLAB_ROOT is
// set, else the one in the source tree this was built from.
std::string resolveDataPath(const std::string& name, const std::string& baseDir = "");

// The project's root folder (datasets/, shaders/): $VOXLAB_ROOT when set,
// else the source tree this was built from.
std::string projectRoot();

}  // namespace voxlab
