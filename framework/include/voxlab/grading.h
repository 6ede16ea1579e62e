// voxlab: grading a stage — its manifest, the tolerances, and the score.
//
// Each stage folder (reference/<stage>/, mirrored in assignments/) holds a
// manifest, grading.json:
//
//   {
//     "title": "Maximum intensity projection",
//     "order": 3,                            // its place in teaching order
//     "points": 10,
//     "about": "what the scenes test",
//     "scenes": [ {"name": "bonsai_oblique", "scene": "scenes/bonsai_oblique.json",
//                  "weight": 1, "tolerance": {"max_flip": 0.03, "why": "..."}},
//                 {"name": "...", "scene": "...", "hidden": true} ],  // graded, never shipped
//     "checks": [ {"name": "phong_random", "weight": 1} ],    // function_checks.h
//     "files": ["mip.glsl"],                 // optional: the stage's source files
//     "cpp_functions": ["planeBoxPolygon"]   // C++ stages: the functions it defines
//   }
//
// A stage's files are what a submission hands in for it: by default the
// .glsl, .frag, .vert and .cpp files of the manifest's folder. Only these
// (and GLSL helpers beside them) are taken from a submission, and only its
// .cpp files among them are compiled.
//
// A scene is rendered by the submission and by the reference (or read from
// the shipped golden image) and compared on the 8-bit images:
//   fraction_over  share of pixels where some channel differs by more than
//                  max_difference grey levels; must be <= max_fraction;
//   largest_cluster the largest 8-connected group of pixels off by more
//                  than cluster_difference grey levels; must be
//                  <= max_cluster pixels (image_metrics.h: noise scatters,
//                  a mistake on a thin feature clusters);
//   ssim           mean SSIM (image_metrics.h); must be >= min_ssim;
//   flip_mean      mean FLIP error (flip.h); must be <= max_flip;
//   psnr, ssim_min, flip_max, max_difference: shown, not scored.
// Each scored metric gives a ratio r = its value / its bound (for SSIM,
// (1 - ssim) / (1 - min_ssim)); the worst ratio decides. A scene passes at
// r <= 1 and earns full credit; its credit then falls linearly to zero at
// r = 3 ("three times the threshold"). A function check passes when every
// case matches the reference; its credit falls linearly with the share of
// failing cases, to zero at 10% (a wrong light vector fails only the cases
// with a highlight, about 15%). A stage's score is its points times the
// weighted mean credit of its scenes and checks.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "voxlab/image.h"

namespace voxlab {

// The default tolerances, in one place. Calibrated so that the reference
// passes against itself rendered another way (hardware instead of explicit
// trilinear filtering, another llvmpipe thread count), and every mutant in
// tests/mutants/ fails (see tests/test_grader_mutants.cpp).
// The cluster bound: the reference rendered another way (the other
// filtering path, another thread count) has no group of more than 1 pixel
// off by more than 8 levels, nor of 2 off by more than 4
// (GradingCalibration prints this); 4 pixels off by 16 leaves room for that
// noise, while a wrong thin feature or small structure fails.
struct Tolerance {
    double maxDifference = 4.0;  // grey levels of 255
    double maxFraction = 0.005;
    double clusterDifference = 16.0;  // grey levels: "badly wrong"
    double maxCluster = 4.0;          // pixels of one connected group of badly wrong ones
    double minSsim = 0.98;
    double maxFlip = 0.02;
};

struct GradedScene {
    std::string name;
    std::string scenePath;  // absolute
    double weight = 1.0;
    bool hidden = false;    // graded, but left out of the student release and of `voxlab check`
    Tolerance tolerance;
};

struct GradedCheck {
    std::string name;
    double weight = 1.0;
};

struct StageManifest {
    std::string stage;
    std::string title;
    std::string about;
    int order = 0;
    double points = 10.0;
    std::vector<GradedScene> scenes;
    std::vector<GradedCheck> checks;
    std::vector<std::string> files;         // the stage's source files, by name
    std::vector<std::string> cppFunctions;  // stage_library.h names, for C++ stages
};

// Reads ROOT/<stage>/grading.json. Errors name the file and the key.
StageManifest loadStageManifest(const std::string& root, const std::string& stage);

// Every stage under ROOT (each folder with a grading.json), in teaching
// order ("order", then the name). A manifest that does not load is an error:
// a stage is never silently left out.
std::vector<StageManifest> stageManifests(const std::string& root);

struct ImageMetrics {
    double fractionOver = 0.0;
    double maxDifference = 0.0;  // grey levels
    int largestCluster = 0;      // pixels
    double ssim = 1.0, ssimMin = 1.0;
    double flipMean = 0.0, flipMax = 0.0;
    double psnr = 0.0;           // dB; infinity for equal images
};

// Compares `submission` with `expected` (both as read from PNG). When
// `flipMap` is given it receives the FLIP heat map (magma colours).
ImageMetrics compareForGrading(const Image& expected, const Image& submission, const Tolerance& tolerance,
                               Image* flipMap = nullptr, Image* differenceMap = nullptr);

// The worst ratio of a metric to its bound (see above), and the credit in [0, 1].
double toleranceRatio(const ImageMetrics& m, const Tolerance& t);
double creditForRatio(double ratio);
double creditForFailedCases(double failedFraction);

nlohmann::json toJson(const ImageMetrics& m);
nlohmann::json toJson(const Tolerance& t);

// The functions of a stage's files that still hold the starter code's stub
// (a `not_implemented();` call in GLSL, `throw NotImplemented(` in C++), by
// name, in file order.
std::vector<std::string> unimplementedFunctions(const std::string& stageFolder);

}  // namespace voxlab
