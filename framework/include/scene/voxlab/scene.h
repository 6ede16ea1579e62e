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
//     "transfer_function": [ {"value": 40, "color": [1,1,1], "alpha": 0}, ... ],
//                                            // or a path to such a JSON file
//     "roi": {"min": [0, 0, 10], "max": [256, 256, 90]},   // cropping box, voxel coordinates
//     "labels": {                            // a label map on the dataset's grid (tagged
//       "volume": "tooth_labels.nrrd",       // volume rendering), see LabelMap below
//       "sampling": "nearest",               // or "masks"
//       "classes": [{"label": 1, "name": "enamel", "transfer_function": ..., "visible": true}],
//       "distance": {"to": 3, "transfer_function": ..., "apply_to": [1, 2]}
//     },
//     "fusion": {"dataset": "pet.nrrd", "mode": "sum", ...},  // a second volume, see Fusion
//     "clip_planes": [{"point": [64, 64, 64], "normal": [0, 0, 1]}]   // up to 6
//   }
//
// Stages bring more sections, each read and written by its stage
// (framework/stages/STAGE/section.cpp, voxlab/scene_section.h), such as the
// cutting plane's and the 2D transfer function's; `voxlab list --sections`
// prints them as a scene writes them.
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
#include "voxlab/project_root.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"

namespace voxlab {

// How sample_volume() reads between voxels:
//   nearest    the voxel that contains the point;
//   trilinear  the 8 surrounding voxels blended in the shader, in float
//              (the "sampling" stage, reference/sampling/sampling.glsl);
//   hardware   the GPU's own linear texture filtering (fast; on many GPUs
//              its weights have only 8 bits);
//   bspline    the cubic B-spline of the 4x4x4 voxels around the point, on
//              coefficients prefiltered so that it interpolates the voxels
//              (bspline.h), smooth (C2), no overshoot of the coefficients;
//   catmull-rom  the Catmull-Rom cubic of the 4x4x4 voxels: interpolates
//              them directly, C1, reproduces quadratics, may overshoot.
// The two cubic ones are the "cubic" stage (reference/cubic/cubic.glsl);
// with them gradients are the kernel's own derivative.
enum class Interpolation { Nearest, Trilinear, Hardware, BSpline, CatmullRom };
inline bool isCubic(Interpolation i) { return i == Interpolation::BSpline || i == Interpolation::CatmullRom; }
const char* interpolationName(Interpolation i);
Interpolation parseInterpolation(const std::string& name);  // throws voxlab::Error

// A renderer parameter's value as written in a scene or on the command
// line; the renderer's declared ParameterSpec checks and converts it.
using ParameterValues = std::map<std::string, double>;

// An axis-aligned cropping box in voxel coordinates: the volume's own box is
// [0, dims] on each axis (voxel i spans [i, i+1]). Every renderer samples
// only inside it.
struct RegionOfInterest {
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};
};

// A plane that splits the view. The scene's renderer, transfer function and
// parameters draw the half-space the normal points into
// (dot(p - point, normal) >= 0); the other half-space is drawn by
// `otherRenderer` with its own transfer function and parameters, or not at
// all when otherRenderer is "none".
struct CuttingPlane {
    std::optional<glm::dvec3> point;  // voxel coordinates; default: the volume's centre
    glm::dvec3 normal{1.0, 0.0, 0.0};  // world direction, any length > 0
    std::string otherRenderer = "none";
    std::optional<TransferFunction> otherTransferFunction;
    ParameterValues otherParameters;
};

// One class of a label map: how the voxels that carry `label` are shown.
struct LabelClass {
    int label = 0;  // 0..kMaxLabel
    std::string name;
    std::optional<TransferFunction> transferFunction;  // default: the scene's own
    bool visible = true;
};

// A distance-based transfer function (Tappenbeck et al. 2006, "distance to
// the tumour"): the Euclidean distance (world units) from each voxel to the
// nearest voxel labelled `to`, computed on the CPU, drives a second transfer
// function over distance. A sample whose label is in `applyTo` (default:
// every label but `to`) takes that function's colour, and its opacity is
// multiplied by that function's opacity.
struct LabelDistance {
    int to = 1;
    TransferFunction transferFunction;
    std::vector<int> applyTo;
};

// How a sample between voxels finds its label. Labels are categories, never
// interpolated: 2.5 is not "between liver and kidney".
//   nearest  the label of the voxel that contains the sample;
//   masks    each label's indicator (1 on its voxels, 0 elsewhere)
//            interpolated trilinearly, and the sample's colour the blend of
//            the labels' classifications by those weights (smooth borders).
enum class LabelSampling { Nearest, Masks };

// A label map: a volume of whole numbers on the dataset's grid, one
// transfer function per label (tagged volume rendering). Label 0 means "no
// label". A label without a class of its own, label 0 included, is shown
// with the scene's transfer function.
constexpr int kMaxLabel = 65535;
constexpr std::size_t kMaxLabelClasses = 255;
struct LabelMap {
    std::string volume;  // resolved path or phantom spec
    LabelSampling sampling = LabelSampling::Nearest;
    std::vector<LabelClass> classes;
    std::optional<LabelDistance> distance;

    // The class of `label`, or nullptr when it has none.
    const LabelClass* find(int label) const;
};

// A second scalar volume shown with the first (image fusion). It covers the
// same box as the first: a different grid is resampled onto it by
// position in the box. Each volume is classified by its own transfer
// function (the second's default: a grey ramp over its window).
//   checkerboard   3D squares of `checkerSize` voxels (of the first volume)
//                  alternate between the two volumes' classifications;
//   split          the second volume on the negative side of the plane
//                  (splitPoint, splitNormal), the first on the positive;
//   color_opacity  colour from the second volume, opacity from the first
//                  (anatomy from CT, function from PET);
//   sum            the two classifications added, premultiplied, opacity
//                  clamped to 1.
enum class FusionMode { Checkerboard, Split, ColorOpacity, Sum };
const char* fusionModeName(FusionMode mode);
FusionMode parseFusionMode(const std::string& name);  // throws voxlab::Error
struct Fusion {
    std::string dataset;  // resolved path or phantom spec
    FusionMode mode = FusionMode::Sum;
    std::optional<glm::dvec2> window;  // default: the second volume's min..max
    std::optional<TransferFunction> transferFunction;
    double checkerSize = 16.0;
    std::optional<glm::dvec3> splitPoint;  // voxel coordinates of the first volume; default: the centre
    glm::dvec3 splitNormal{1.0, 0.0, 0.0};
};

// A clip plane keeps the half-space its normal points into,
// dot(p - point, normal) >= 0; a scene has up to kMaxClipPlanes of them, on
// top of the region of interest. Every renderer samples only what all of
// them keep.
constexpr std::size_t kMaxClipPlanes = 6;
struct ClipPlane {
    glm::dvec3 point{0.0};        // voxel coordinates
    glm::dvec3 normal{0.0, 0.0, 1.0};  // world direction, any length > 0
};

// Limits every way of writing a scene (JSON, command line, viewer) obeys.
constexpr int kMaxImageSize = 8192;  // pixels, per side
constexpr double kMaxGpuMemoryMiB = 1 << 24;  // 16 TiB: "gpu_memory" in [1, this]
constexpr double kMaxStep = 64.0;    // in smallest spacings; steps are in (0, kMaxStep]

struct Scene {
    std::string dataset;          // resolved path or phantom spec
    std::string renderer = "mip";
    CameraSpec camera;
    int width = 256;
    int height = 256;
    double step = 0.5;            // in units of the smallest voxel spacing
    Interpolation interpolation = Interpolation::Trilinear;
    // Empty-space skipping (empty_space.h): leaves out samples that cannot
    // change the image. On by default; the grader turns it off.
    bool skipEmptySpace = true;
    // The GPU memory the volume's textures may take, in MiB ("gpu_memory",
    // --gpu-memory); past it the volume is drawn in bricks (volume_bricks.h).
    // Default: RenderEngine::defaultGpuMemoryBudget().
    std::optional<double> gpuMemoryMiB;
    std::optional<glm::dvec2> window;  // default: the dataset's min..max
    glm::vec3 background{0.0f};
    ParameterValues parameters;
    std::optional<TransferFunction> transferFunction;
    std::optional<TransferFunction2D> transferFunction2D;
    std::optional<RegionOfInterest> roi;
    std::optional<CuttingPlane> cuttingPlane;
    std::optional<LabelMap> labels;
    std::optional<Fusion> fusion;
    std::vector<ClipPlane> clipPlanes;

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
// The project's datasets/ folder is projectRoot()/datasets
// (voxlab/project_root.h).
std::string resolveDataPath(const std::string& name, const std::string& baseDir = "");


}  // namespace voxlab
