// voxlab: the grader. It grades submissions stage by stage against the
// reference solution (or, for a student's self-check, against the golden
// outputs shipped with a student release).
//
// For each submission and stage, in its own child process (child_process.h)
// with a time limit, a memory cap and writes confined to the stage's report
// folder, the stage's scenes are rendered and its function checks run; the
// parent then compares them with the expected outputs (grading.h) and
// writes, per submission:
//   REPORT/report.json    everything, for tools (schema in html_report.h)
//   REPORT/results.json   Gradescope's autograder format
//   REPORT/index.html     reference | submission | FLIP heat map | difference
//                         for every scene, with the metrics; offline
//   REPORT/<stage>/       the images
// When grading, a stage runs with only that stage taken from the
// submission: every other stage comes from the reference, so one mistake
// is not counted twice. A self-check runs the student's whole tree.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace voxlab {

struct GraderOptions {
    std::string voxlab;           // the executable that runs workers; empty: this one
    std::string referenceRoot;    // grading manifests and, when rendering them, the expected outputs
    std::string expectedDir;      // expected outputs: rendered here from referenceRoot unless `shipped`
    bool shipped = false;         // expectedDir already holds the outputs (a release's goldens, or
                                  // an earlier renderExpectedOutputs): do not render them again; the
                                  // stages not graded then run this program's own C++ stages
    bool isolateStage = true;     // false for a self-check: the submission's whole tree runs
    bool hiddenScenes = true;     // grade scenes marked "hidden" (false: `voxlab check`, a release's goldens)
    std::vector<std::string> stages;  // empty: every stage with a manifest, in teaching order
    std::map<std::string, double> points;  // stage -> points instead of its manifest's (an assignment file)
    nlohmann::json tolerance = nlohmann::json::object();  // set over every scene's (--tolerance KEY=VALUE)
    double timeLimit = 60.0;          // seconds per stage
    std::size_t memoryLimit = std::size_t(4) << 30;
    int jobs = 1;                 // stages graded at once (each a process)
    int renderThreads = 0;        // llvmpipe threads per process; 0: $LP_NUM_THREADS, else cores / jobs
    bool progress = true;         // a progress bar on stderr
    bool cache = true;            // keep the expected outputs between runs (expected_cache.h):
                                  // a second run with the same inputs copies them instead of rendering
    // Called on each submission's report before it is written (an
    // assignment file's visibility and late policy: assignment.h).
    std::function<void(nlohmann::json& report)> adjustReport;
};

struct Submission {
    std::string name;    // shown in reports and the gradebook (made safe text there)
    std::string folder;  // shaped like assignments/ (prepareSubmission: in the grader's copy of the upload)
    std::string reportDir;
    std::vector<std::string> stages;  // empty: the options' stages
    std::string layoutNote;           // how the upload was brought into shape (submissionRoot), if it was
    std::string upload;               // the upload as given, for the report ("": `folder`)
    std::string problem;              // why it cannot be graded (upload.h); set: every stage is an error
};

// Renders the expected outputs of `options.stages` from the reference into
// options.expectedDir (what a student release ships as goldens). The
// reference's C++ stages, compiled to EXPECTED/reference_stages.so for the
// stage runs, are removed when it returns or throws: the folder keeps
// EXPECTED/<stage>/<scene>.png and EXPECTED/<stage>/checks/<check>.json only.
// gradeSubmissions() without `shipped` renders them the same way and keeps
// the library until its grading ends.
void renderExpectedOutputs(const GraderOptions& options);

// Grades every submission; returns their report.json contents, in order.
// Never throws for anything a submission does: a submission with a
// `problem`, or whose report cannot be written, still gets a report whose
// "status" is "error", with the reason as its "message" and every stage an
// error worth 0 points. Text from a submission reaches the reports only as
// safe text (untrusted_text.h).
std::vector<nlohmann::json> gradeSubmissions(const std::vector<Submission>& submissions,
                                             const GraderOptions& options);

// Gradescope's results.json for a report. With the report's folder, each
// scene that did not pass but has the submission's image shows it, the
// expected image and the difference map in its output ("output_format":
// "html", PNG data: URIs, each image at most kResultsImageSide px on its
// longer side), the first such scene of every stage first (stages not
// implemented yet last), until the images take kResultsImageBudget
// characters; the others say so.
inline constexpr std::size_t kResultsImageBudget = std::size_t(1) << 20;
inline constexpr int kResultsImageSide = 256;
nlohmann::json gradescopeResults(const nlohmann::json& report, const std::string& reportDir = "");

// A terminal table: stage, status, score, message.
std::string summaryTable(const nlohmann::json& report);

// The stage names graded by default: every folder under `root` with a
// grading.json, in teaching order (the manifests' "order"). Throws when a
// manifest does not load, so that no stage is silently never graded.
std::vector<std::string> gradedStages(const std::string& root);

}  // namespace voxlab
