// voxlab: the grader's HTML reports, readable offline (no external CSS,
// scripts, fonts or URLs; images are relative links into the report folder).
//
// A submission's report is written from its results (report.json). Every
// field may be missing except those marked *; image paths are relative to
// the report folder:
//
//   {
//     "submission": "/path/to/alice", "name": "alice", "graded_at": "2026-11-22T07:10:00Z",
//     "mode": "grade | check", "against": "shipped | reference" (where the expected outputs came from),
//     "machine": "Mesa llvmpipe ...", "sandbox": ["pid, network and ipc namespaces", "landlock reads", ...],
//     "elapsed_s": 41.2,
//     "score": 87.5, "max_score": 140,
//     "stages": [
//       {"stage"*: "mip", "title": "Maximum intensity projection", "about": "what the stage tests",
//        "score"*: 8.2, "max_score"*: 10,
//        "status"*: "passed | failed | not_implemented | compile_error | timeout | crashed | error | example",
//        "message": "one line", "log": "compiler log, mapped to the student's files", "elapsed_s": 3.1,
//        "scenes": [
//          {"name"*: "bonsai_oblique", "score": 1.6, "max_score": 2, "status"*: "passed | failed | error",
//           "message": "one line", "about": "what the scene shows", "scene_file": "mip/scenes/bonsai_oblique.json",
//           "setup": "dataset: bonsai.nrrd; renderer: mip; ...",
//           "images": {"reference": "mip/x.reference.png", "submission": "mip/x.submission.png",
//                      "flip": "mip/x.flip.png", "difference": "mip/x.difference.png"},
//           "metrics": {"fraction_over": 0.012, "max_difference": 37, "ssim": 0.973, "ssim_min": 0.41,
//                       "flip_mean": 0.031, "flip_max": 0.62, "psnr": 31.2},   // psnr null: identical
//           "tolerance": {"max_difference": 4, "max_fraction": 0.005, "min_ssim": 0.98, "max_flip": 0.02}}],
//        "checks": [
//          {"name"*: "phong_random", "description": "...", "score": 0, "max_score": 2, "status"*: "failed",
//           "message": "37 of 200 cases differ", "examples": ["n=(0,0,1) ... expected (..) got (..)"],
//           "inputs": {"seed": "0x5EED000A", "volume": {"dims": [6, 7, 5], "spacing": [..], "extent": [..],
//                      "values": "data value = ..."}, "units": "..."}}]}
//     ]
//   }
//
// A class's gradebook is either an array of such results or an object
// {"title": "...", "graded_at": "...", "submissions": [results, ...]}; each
// entry needs only "name" (its report is NAME/index.html unless it gives
// "report", a relative link) and may carry "status" and "message" for the
// submission as a whole (e.g. "error", "the C++ stages did not build").
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace voxlab {

// A stage of a submission that did not pass, for the class report and the
// gradebook's problems column.
struct StageProblem {
    std::string stage, status, message;
};

// The submission's stages that did not pass (status other than passed and
// example), worst first: compile_error, crashed, timeout, error (and any
// status not named here), failed, not_implemented; in grading order within
// each.
std::vector<StageProblem> stageProblems(const nlohmann::json& results);

// The same in one line for a CSV cell, worst first: "mip: compile_error
// (mip/mip.glsl:20: error: ...); iso: failed; shading: not_implemented".
// Messages are given for the first four kinds only.
std::string problemsSummary(const nlohmann::json& results);

// The gradebook as CSV text: a header (name, score, max_score, every stage
// of any report in the order they first appear, problems) and a row per
// report: its total, each stage's score (empty where it has none), and its
// problems (problemsSummary, or "not graded: " and the reason for a
// submission whose "status" is "error"). Text cells go through csvCell()
// (untrusted_text.h): valid UTF-8, quoted where needed, never a formula.
std::string gradebookCsv(const std::vector<nlohmann::json>& reports);

// Writes reportDir/index.html for one graded submission from its results
// (the schema above). Image paths in the results are relative to reportDir;
// an image that is named but not on disk is shown as a placeholder. Creates
// no folders. Throws voxlab::Error when the file cannot be written.
void writeHtmlReport(const nlohmann::json& results, const std::string& reportDir);
// The page writeHtmlReport() writes, as text (it reads the images' sizes).
std::string htmlReportPage(const nlohmann::json& results, const std::string& reportDir);

// Writes dir/index.html for a class: one row per submission (name, score,
// per-stage scores, status), each linking to its report folder, sortable by
// clicking a column's heading. What went wrong is visible text: each cell
// names its stage's problem (compile error, crashed, ...) and the name's cell
// lists the problems, worst first (stageProblems). Stages worth 0 points in
// every submission (a worked example) get no column. Throws voxlab::Error
// when the file cannot be written.
void writeClassHtmlReport(const nlohmann::json& gradebook, const std::string& dir);
// The page writeClassHtmlReport() writes, as text.
std::string classHtmlReportPage(const nlohmann::json& gradebook);

}  // namespace voxlab
