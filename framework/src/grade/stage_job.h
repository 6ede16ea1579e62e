// voxlab grader internals: running one stage of one implementation in a
// child process, and scoring what it produced.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "voxlab/grader.h"
#include "voxlab/grading.h"

namespace voxlab::grading {

// Where one stage of one implementation runs.
struct StageRun {
    std::string stage;
    std::string implementationRoot;  // the tree the stage's files come from
    std::string outputDir;           // the worker writes here (and only here)
    std::string workDir;             // snapshot, stage library, compiler output
    std::string suffix;              // appended to image names (".submission")
};

// What the stage's process did: how it ended, and the compiler log when
// building the stage's C++ failed.
struct RunOutcome {
    bool compiled = true;
    std::string compileLog;
    bool finished = false;
    std::string ended;  // ChildResult::describe, "ok" when it finished
    std::string output; // the worker's own output (for the report's log)
};

// Copies the stage (isolated) or uses the tree as it is, builds the C++ of
// the implementation into a stage library if there is any, and runs
// `voxlab grade-worker` for the stage under the options' limits.
RunOutcome runStage(const StageRun& run, const GraderOptions& options);

// Scores a finished (or failed) run against the expected outputs; returns
// the stage's entry of report.json.
nlohmann::json scoreStage(const StageRun& run, const RunOutcome& outcome, const StageManifest& manifest,
                          const GraderOptions& options, const std::string& submissionFolder);

// The executable that runs workers.
std::string voxlabExecutable(const GraderOptions& options);

}  // namespace voxlab::grading
