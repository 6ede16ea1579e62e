// voxlab grader internals: running one stage of one implementation in a
// sandboxed child process, and scoring what it sent back.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "voxlab/grader.h"
#include "voxlab/grading.h"
#include "voxlab/worker_results.h"

namespace voxlab::grading {

// Where one stage of one implementation runs.
struct StageRun {
    std::string stage;
    std::string implementationRoot;  // the tree the stage's files come from
    std::string workDir;             // snapshot, task, libraries: the worker reads only these (removed after)
    bool graded = false;             // take only this stage from the tree, checked (a submission)
};

// What happened: a problem with the submission's files found before
// running, the C++ build, how the worker ended, and what it sent.
struct RunOutcome {
    std::string problemKind;  // "not_implemented" or "error" when the stage was not run
    std::string problem;      // "mip/mip.glsl is missing", ...
    bool compiled = true;
    std::string compileLog;
    bool finished = false;
    std::string ended;   // ChildResult::describe, "ok" when it finished
    std::string output;  // the worker's own output (for the report's log)
    std::vector<std::string> sandbox;
    std::vector<std::string> stubs;  // functions still holding the starter code's stub
    WorkerResults results;
};

// Takes a snapshot of the stage (graded: only the manifest's files, each a
// regular file under the size limit), builds its C++ into a stage library if
// it has any, and runs `voxlab grade-worker` in the sandbox.
RunOutcome runStage(const StageRun& run, const StageManifest& manifest, const GraderOptions& options);

// Scores a run against the expected outputs, writing the report's images
// into `reportStageDir`; returns the stage's entry of report.json.
nlohmann::json scoreStage(const StageRun& run, const RunOutcome& outcome, const StageManifest& manifest,
                          const GraderOptions& options, const std::string& reportStageDir);

// The executable that runs workers.
std::string voxlabExecutable(const GraderOptions& options);

// Processes and threads one stage may have at once, build and run together.
constexpr int kStageProcesses = 64;

// A stage file larger than this is refused (it is no shader).
constexpr std::uintmax_t kMaxStageFileBytes = 1u << 20;

}  // namespace voxlab::grading
