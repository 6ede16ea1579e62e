// voxlab: function-level checks for the grader, where images are blind.
//
// An image shows a stage's function only at the inputs a scene happens to
// reach: a Phong highlight on the unlit side, a trilinear weight off by half
// a voxel on a smooth field, or a polygon whose vertices come in the wrong
// order can all look right. A function check calls the stage's function
// directly on a fixed set of pseudo-random inputs (std::mt19937 with a fixed
// seed, mapped to numbers by explicit arithmetic, so the inputs are the same
// on every run and machine) and records inputs and outputs as JSON:
//
//   {"check": "phong_random", "stage": "shading", "seed": 1592590337, "not_implemented": false,
//    "fixture": {...},             // shared inputs (a volume), if any
//    "cases": [{"function": "phong", "input": {...}, "output": ...}, ...]}
//
// "not_implemented" is true when some call reached a GLSL stub's
// not_implemented(). A NaN output is stored as JSON null (and fails).
//
// Each stage's checks live in its folder (framework/stages/STAGE/check.cpp,
// voxlab/function_check_support.h). GLSL functions run in small probe
// fragment shaders beside them (framework/stages/STAGE/*_probe.frag), one
// case per pixel, through ShaderLibrary::forImplementation(root); they need
// a current GL context. C++ functions are called through cppStages(), so a
// loaded stage library is what gets checked.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "voxlab/function_check_info.h"

namespace voxlab {

// Names of every check, and the stage each belongs to.
const std::vector<FunctionCheckInfo>& functionChecks();

// Runs the check's function(s) on the check's fixed pseudo-random inputs
// with the implementation at `implementationRoot` ("" for reference/).
// Throws what the code under test throws: voxlab::ShaderError for compile
// and link errors, voxlab::NotImplemented from a C++ stub; voxlab::Error for
// an unknown check or a missing implementation folder. Any other exception
// a C++ stage throws on one case is recorded as that case's output
// ({"error": "..."}), which fails the comparison.
nlohmann::json runFunctionCheck(const std::string& name, const std::string& implementationRoot);

struct CheckComparison {
    int cases = 0, failed = 0;
    std::string summary;                // one line, e.g. "37 of 200 cases differ; worst |Δ| 0.41"
    std::vector<std::string> examples;  // up to 3 failing cases: inputs, expected, got
    // How to reproduce the inputs, from the expected results: {"seed": "0x5EED000A",
    // "volume": {"dims": [6, 7, 5], "spacing": [...], "extent": [...], "values": "..."},
    // "units": "..."}; each key only where known (empty for checks without a volume or seed).
    nlohmann::json inputs = nlohmann::json::object();
};

// Compares a submission's outputs (`actual`) with the expected (reference)
// outputs of the same check; the tolerances are stated per check in the
// stage's check.cpp. Throws voxlab::Error when the two were not run on the
// same inputs (a different check, or expected outputs from another version).
CheckComparison compareFunctionCheck(const std::string& name, const nlohmann::json& expected,
                                     const nlohmann::json& actual);

}  // namespace voxlab
