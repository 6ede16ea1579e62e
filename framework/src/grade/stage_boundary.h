// voxlab grader internals: a graded stage uses only its own code, the
// framework's, and the stages its manifest `requires`.
//
// A graded GLSL stage is compiled together with other stages' reference
// code: its prerequisites, and the stages the framework's own shaders pull
// in (volume.glsl includes sampling and cubic, ray.glsl the cutting plane's,
// lighting.glsl shading, ...). Another stage's reference may solve the
// graded one (attenuated MIP with no attenuation is MIP), so the grader
// checks the submission's GLSL before it runs: it may include only its own
// folder, the framework's files and its prerequisites', and may call no
// function that only a stage outside those defines. Token pasting (`##`),
// which could spell such a name without writing it, is refused in a graded
// stage's files. All of it is a linear scan of the text: no regular
// expression runs on a submission.
#pragma once

#include <string>
#include <vector>

namespace voxlab::grading {

// The stages `stage` requires (its manifest's "requires"), and theirs.
std::vector<std::string> requiredStages(const std::string& referenceRoot, const std::string& stage);

// The stages whose GLSL the framework's own shaders include (shaders/voxlab
// and renderers, the stage folders' entry shaders and precomputation
// passes; not the probes, which each include their own stage), found by
// reading those files and the shaders renderers make from templates.
std::vector<std::string> frameworkStages(const std::string& referenceRoot);

// Checks the graded stage's GLSL files in `impl`/`stage` against the
// boundary above; `allowed` are the stages it may use besides itself. The
// function names of every other stage are read from `referenceRoot`, the
// framework's (always allowed) from `shadersRoot`/voxlab. Returns "" or a
// compiler-style message ("mip/mip.glsl:12:5: ...").
std::string checkStageBoundary(const std::string& impl, const std::string& stage,
                               const std::vector<std::string>& allowed, const std::string& referenceRoot,
                               const std::string& shadersRoot);

}  // namespace voxlab::grading
