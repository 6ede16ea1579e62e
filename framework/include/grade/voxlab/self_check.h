#pragma once
// voxlab: one stage checked in this process, against expected images.
//
// What `voxlab check` does for a stage's scenes, without the grader's
// sandbox and child processes: the browser workbench (web/) runs it on the
// student's own code in the student's own page, where there is nothing to
// protect. The verdict on each image is the grader's own code
// (compareForGrading, sceneVerdict and the stage's tolerances from its
// grading.json), and so is the arithmetic of the score, over the scenes
// only: a stage's function checks (grading.h: GradedCheck) run natively,
// and the result says how many were left to `voxlab check`.

#include <string>

#include <nlohmann/json.hpp>

namespace voxlab {

struct SelfCheckOptions {
    std::string tree;         // the stage folders checked (assignments/, or reference/ to try the model)
    std::string expectedDir;  // EXPECTED/<stage>/<scene>.png, rendered by the reference
    std::string outDir;       // OUT/<scene>.{submission,flip,difference}.png are written here
};

// {"stage", "title", "scenes": [{name, status, message, metrics, credit,
//  weight, images}], "checks_native_only", "score", "max_score", "status"}.
// Hidden scenes are left out, as in `voxlab check`. Throws voxlab::Error
// for a stage whose grading.json does not load.
nlohmann::json selfCheckStage(const std::string& stage, const SelfCheckOptions& options);

}  // namespace voxlab
