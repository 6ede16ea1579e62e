// voxlab grader: grading submissions, stage by stage, in parallel
// processes (see grader.h).
#include "voxlab/grader.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "voxlab/expected_cache.h"
#include "stage_job.h"
#include "voxlab/atomic_file.h"
#include "voxlab/image.h"
#include "voxlab/child_process.h"
#include "voxlab/error.h"
#include "voxlab/html_report.h"
#include "voxlab/stage_library.h"
#include "voxlab/untrusted_text.h"

namespace voxlab {

namespace fs = std::filesystem;
using nlohmann::json;
using grading::RunOutcome;
using grading::StageRun;

std::vector<std::string> gradedStages(const std::string& root) {
    std::vector<std::string> stages;
    for (const StageManifest& m : stageManifests(root)) stages.push_back(m.stage);
    return stages;
}

namespace {

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

std::string isoTime() {
    const std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return buf;
}

// A progress bar on stderr ("[#####.....] 12/30  alice: mip"), redrawn in
// place on a terminal and printed every tenth of the way otherwise.
class Progress {
public:
    Progress(int total, bool show) : total_(total), show_(show && total > 0), tty_(isatty(2)) {}
    void done(const std::string& what) {
        std::lock_guard<std::mutex> lock(mutex_);
        ++count_;
        if (!show_) return;
        const int width = 30, filled = total_ ? width * count_ / total_ : width;
        if (tty_) {
            std::fprintf(stderr, "\r[%s%s] %d/%d  %-40.40s", std::string(filled, '#').c_str(),
                         std::string(width - filled, '.').c_str(), count_, total_, terminalLine(what, 40).c_str());
            if (count_ == total_) std::fprintf(stderr, "\n");
        } else if (count_ == total_ || (count_ * 10 / total_) != ((count_ - 1) * 10 / total_)) {
            std::fprintf(stderr, "%d/%d done (%s)\n", count_, total_, terminalLine(what, 200).c_str());
        }
    }

private:
    int total_, count_ = 0;
    bool show_, tty_;
    std::mutex mutex_;
};

// Runs jobs 0..n-1 on `workers` threads.
void parallelFor(int n, int workers, const std::function<void(int)>& job) {
    std::atomic<int> next{0};
    std::vector<std::thread> threads;
    for (int w = 0; w < std::max(1, std::min(workers, n)); ++w)
        threads.emplace_back([&] {
            for (int i; (i = next++) < n;) job(i);
        });
    for (std::thread& t : threads) t.join();
}

std::vector<std::string> chosenStages(const GraderOptions& options) {
    if (!options.stages.empty()) {
        for (const std::string& s : options.stages)
            if (!fs::exists(fs::path(options.referenceRoot) / s / "grading.json"))
                throw Error("unknown stage '" + s + "' (no " + options.referenceRoot + "/" + s + "/grading.json)");
        std::vector<std::string> stages;  // in teaching order, once each
        for (const std::string& s : gradedStages(options.referenceRoot))
            if (std::find(options.stages.begin(), options.stages.end(), s) != options.stages.end()) stages.push_back(s);
        return stages;
    }
    return gradedStages(options.referenceRoot);
}

// A stage's manifest as graded: without its hidden scenes for a self-check
// or a release's goldens. (Every stage graded was chosen through
// stageManifests(), which has checked its functions against its files.)
StageManifest gradedManifest(const std::string& stage, const GraderOptions& options) {
    StageManifest m = loadStageManifest(options.referenceRoot, stage);
    if (const auto it = options.points.find(stage); it != options.points.end()) m.points = it->second;
    for (GradedScene& scene : m.scenes) scene.tolerance = overTolerance(scene.tolerance, options.tolerance, "--tolerance");
    if (!options.hiddenScenes)
        m.scenes.erase(std::remove_if(m.scenes.begin(), m.scenes.end(), [](const GradedScene& s) { return s.hidden; }),
                       m.scenes.end());
    return m;
}

// Renders one stage of the reference and saves what it sent as the
// expected outputs (EXPECTED/<stage>/<scene>.png, checks/<check>.json).
void renderExpectedStage(const std::string& stage, const GraderOptions& options) {
    const StageManifest manifest = gradedManifest(stage, options);
    const fs::path out = fs::path(options.expectedDir) / stage;
    const StageRun run{stage, options.referenceRoot, (fs::path(options.expectedDir) / ".work" / stage).string(), false};
    fs::remove_all(out);
    const RunOutcome outcome = grading::runStage(run, manifest, options);
    if (!outcome.compiled) throw Error(outcome.compileLog);
    if (!outcome.finished) throw Error("the reference " + outcome.ended + "\n" + outcome.output);
    if (!outcome.results.problem.empty()) throw Error(outcome.results.problem);
    for (const auto& [key, error] : outcome.results.errors)
        throw Error("the reference failed: " + key + ": " + error.value("message", ""));
    fs::create_directories(out / "checks");
    // The worker's last line names the GL it rendered with ("gl: OSMesa: llvmpipe ...").
    const std::size_t gl = outcome.output.rfind("gl: ");
    if (gl != std::string::npos)
        writeFileAtomically((out / "gl.txt").string(),
                            outcome.output.substr(gl + 4, outcome.output.find('\n', gl) - gl - 4) + "\n");
    for (const auto& [name, image] : outcome.results.images) savePng(image, (out / (name + ".png")).string());
    for (const auto& [name, result] : outcome.results.checks)
        writeFileAtomically((out / "checks" / (name + ".json")).string(),
                            result.dump(-1, ' ', false, json::error_handler_t::replace) + "\n");
}

// The reference's C++ stages, compiled for the stage runs (stage_job.cpp
// loads them into every worker). The solution, compiled: it is no expected
// output, and a report folder may be handed to a student.
fs::path referenceLibrary(const GraderOptions& options) {
    return fs::path(absolute(options.expectedDir)) / "reference_stages.so";
}

// Removes a file when the run that made it ends, however it ends.
class RemovedAtEnd {
public:
    explicit RemovedAtEnd(fs::path path) : path_(std::move(path)) {}
    RemovedAtEnd(const RemovedAtEnd&) = delete;
    RemovedAtEnd& operator=(const RemovedAtEnd&) = delete;
    ~RemovedAtEnd() {
        std::error_code ec;
        if (!path_.empty()) fs::remove(path_, ec);
    }

private:
    fs::path path_;
};

// The reference's C++ stages as a library, loaded by every graded stage
// (from the cache when the same inputs built it before).
void buildReferenceLibrary(const GraderOptions& options, const std::string& cacheKey) {
    std::vector<std::string> sources;
    for (const std::string& s : gradedStages(options.referenceRoot)) {
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(fs::path(options.referenceRoot) / s, ec))
            if (entry.path().extension() == ".cpp") sources.push_back(entry.path().string());
    }
    if (sources.empty()) return;
    const std::string library = referenceLibrary(options).string();
    if (!cacheKey.empty() && expected_cache::restore(cacheKey, "reference_stages.so", library)) return;
    ChildLimits limits;
    limits.seconds = 300.0;
    const ChildResult built = runChild(stageLibraryBuildCommand(sources, library), limits);
    if (!built.succeeded()) throw Error("the reference's C++ stages do not compile:\n" + built.output);
    if (!cacheKey.empty()) expected_cache::store(cacheKey, "reference_stages.so", library);
}

// A stage's entry in the expected-output cache: as grading renders it, or
// without the hidden scenes.
std::string cacheEntry(const std::string& stage, const GraderOptions& options) {
    return options.hiddenScenes ? stage : stage + "@public";
}

// Copies a stage's expected outputs from the cache; without hidden scenes,
// the grading entry serves too, less the hidden scenes' images.
bool restoreExpectedStage(const std::string& stage, const GraderOptions& options, const std::string& cacheKey) {
    const fs::path out = fs::path(options.expectedDir) / stage;
    if (expected_cache::restore(cacheKey, cacheEntry(stage, options), out.string())) return true;
    if (options.hiddenScenes || !expected_cache::restore(cacheKey, stage, out.string())) return false;
    for (const GradedScene& scene : loadStageManifest(options.referenceRoot, stage).scenes)
        if (scene.hidden) fs::remove(out / (scene.name + ".png"));
    return true;
}

// renderExpectedOutputs, leaving the reference library in place for the
// stage runs that follow. Stages whose outputs the cache holds are copied.
void renderExpectedWithLibrary(const GraderOptions& given) {
    GraderOptions options = given;
    options.referenceRoot = absolute(options.referenceRoot);
    options.expectedDir = absolute(options.expectedDir);
    options.isolateStage = false;
    const std::vector<std::string> stages = chosenStages(options);
    fs::create_directories(options.expectedDir);
    const std::string cacheKey =
        options.cache && expected_cache::folder() ? expected_cache::key(options.voxlab, options.referenceRoot) : "";
    buildReferenceLibrary(options, cacheKey);
    std::vector<std::string> toRender;
    for (const std::string& stage : stages)
        if (cacheKey.empty() || !restoreExpectedStage(stage, options, cacheKey)) toRender.push_back(stage);
    Progress progress(int(toRender.size()), options.progress);
    std::vector<std::string> failures(toRender.size());
    parallelFor(int(toRender.size()), options.jobs, [&](int i) {
        try {
            renderExpectedStage(toRender[i], options);
            if (!cacheKey.empty())
                expected_cache::store(cacheKey, cacheEntry(toRender[i], options),
                                      (fs::path(options.expectedDir) / toRender[i]).string());
        } catch (const std::exception& e) {
            failures[i] = toRender[i] + ": " + e.what();
        }
        progress.done("reference rendered: " + toRender[i]);
    });
    fs::remove_all(fs::path(options.expectedDir) / ".work");
    for (const std::string& f : failures)
        if (!f.empty()) throw Error("rendering the expected outputs: " + f);
    // What grading against this folder (--expected) needs to know of it.
    writeFileAtomically((fs::path(options.expectedDir) / "expected.json").string(),
                        json({{"hidden_scenes", options.hiddenScenes}}).dump(2) + "\n");
}

}  // namespace

void renderExpectedOutputs(const GraderOptions& options) {
    const RemovedAtEnd library(referenceLibrary(options));
    renderExpectedWithLibrary(options);
}

namespace {

// One stage of one submission graded; its entry of report.json.
json gradeStage(const Submission& sub, const std::string& stage, const GraderOptions& options) {
    json entry;
    try {
        const StageManifest manifest = gradedManifest(stage, options);
        const fs::path report = absolute(sub.reportDir);
        const StageRun run{stage, absolute(sub.folder), (report / ".work" / stage).string(), options.isolateStage};
        fs::remove_all(report / stage);
        if (!fs::is_directory(fs::path(sub.folder) / stage)) {
            entry = {{"stage", stage}, {"title", manifest.title}, {"score", 0.0},
                     {"max_score", manifest.points}, {"status", "not_implemented"},
                     {"message", "the submission has no folder " + stage + "/"}};
        } else {
            const RunOutcome outcome = grading::runStage(run, manifest, options);
            entry = grading::scoreStage(run, outcome, manifest, options, (report / stage).string());
        }
        fs::remove_all(run.workDir);
    } catch (const std::exception& e) {
        entry = {{"stage", stage}, {"score", 0.0}, {"max_score", 0.0}, {"status", "error"},
                 {"message", safeText(std::string("grader error: ") + e.what())}};
    } catch (...) {
        entry = {{"stage", stage}, {"score", 0.0}, {"max_score", 0.0}, {"status", "error"},
                 {"message", "grader error (not a std::exception)"}};
    }
    return entry;
}

// The stages of a submission that cannot be graded: each an error worth
// nothing, out of its points, with the reason.
json ungradedStages(const std::vector<std::string>& stages, const std::string& why, const GraderOptions& options) {
    json out = json::array();
    for (const std::string& stage : stages) {
        json entry = {{"stage", stage}, {"score", 0.0}, {"max_score", 0.0}, {"status", "error"}, {"message", why}};
        try {
            const StageManifest manifest = gradedManifest(stage, options);
            entry["title"] = manifest.title;
            entry["max_score"] = manifest.points;
        } catch (const std::exception&) {  // the stage's own error shows where it is graded
        }
        out.push_back(entry);
    }
    return out;
}

// A submission's report.json, from its stages' entries (null: not asked for).
json submissionReport(const Submission& sub, const std::vector<json>& results, double seconds,
                      const std::vector<std::string>& stages, const GraderOptions& options) {
    json report = {{"submission", safeText(absolute(sub.upload.empty() ? sub.folder : sub.upload), kMaxLogBytes)},
                   {"name", safeText(sub.name, kMaxNameBytes)}, {"graded_at", isoTime()},
                   {"mode", options.shipped || !options.isolateStage ? "check" : "grade"},
                   {"against", options.shipped ? "shipped" : "reference"},
                   {"sandbox", sandboxLayers()},
                   {"sandbox_missing", sandboxMissingLayers()},
                   {"elapsed_s", seconds}};
    json graded = json::array();
    for (const json& stage : results)
        if (!stage.is_null()) graded.push_back(stage);
    if (!sub.problem.empty()) {
        report["status"] = "error";
        report["message"] = safeText(sub.problem);
        std::vector<std::string> asked;
        for (const std::string& stage : stages)
            if (sub.stages.empty() || std::count(sub.stages.begin(), sub.stages.end(), stage)) asked.push_back(stage);
        graded = ungradedStages(asked, report["message"], options);
    }
    double score = 0.0, maxScore = 0.0;
    for (const json& stage : graded) {
        score += stage.value("score", 0.0);
        maxScore += stage.value("max_score", 0.0);
    }
    report["score"] = score;
    report["max_score"] = maxScore;
    // The GL the stages ran on (each stage names it; the worker printed it).
    for (const json& stage : graded)
        if (stage.contains("gl") && stage["gl"].is_string() && !report.contains("machine"))
            report["machine"] = safeText(stage["gl"].get<std::string>(), 200);
    report["stages"] = graded;
    if (!sub.layoutNote.empty()) report["layout_note"] = safeText(sub.layoutNote);
    return report;
}

// Writes report.json, results.json and index.html; a failure makes the
// report an error that says so (the batch goes on).
void writeReports(json& report, const Submission& sub, const GraderOptions& options) {
    try {
        if (options.adjustReport) options.adjustReport(report);
        fs::create_directories(sub.reportDir);
        fs::remove_all(fs::path(sub.reportDir) / ".work");
        writeFileAtomically((fs::path(sub.reportDir) / "report.json").string(), reportJsonText(report));
        writeFileAtomically((fs::path(sub.reportDir) / "results.json").string(),
                            reportJsonText(gradescopeResults(report, sub.reportDir)));
        writeHtmlReport(report, sub.reportDir);
    } catch (const std::exception& e) {
        report["status"] = "error";
        report["message"] = safeText(std::string("the report cannot be written: ") + e.what());
    }
}

}  // namespace

std::vector<json> gradeSubmissions(const std::vector<Submission>& submissions, const GraderOptions& given) {
    GraderOptions options = given;
    options.referenceRoot = absolute(options.referenceRoot);
    options.expectedDir = absolute(options.expectedDir);
    const std::vector<std::string> stages = chosenStages(options);
    // Rendered here, the expected outputs come with the reference library,
    // which the graded stages load and which goes when grading ends.
    const RemovedAtEnd library(options.shipped ? fs::path() : referenceLibrary(options));
    if (!options.shipped) renderExpectedWithLibrary(options);

    struct Job {
        std::size_t submission;
        std::size_t stage;
    };
    std::vector<Job> jobs;
    for (std::size_t s = 0; s < submissions.size(); ++s)
        for (std::size_t k = 0; k < stages.size(); ++k)
            if (submissions[s].problem.empty() &&
                (submissions[s].stages.empty() ||
                 std::count(submissions[s].stages.begin(), submissions[s].stages.end(), stages[k])))
                jobs.push_back({s, k});
    std::vector<std::vector<json>> results(submissions.size(), std::vector<json>(stages.size()));
    std::vector<double> seconds(submissions.size(), 0.0);
    std::mutex mutex;
    Progress progress(int(jobs.size()), options.progress);
    parallelFor(int(jobs.size()), options.jobs, [&](int i) {
        const Job& job = jobs[i];
        const Submission& sub = submissions[job.submission];
        const auto start = std::chrono::steady_clock::now();
        json entry = gradeStage(sub, stages[job.stage], options);
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        entry["elapsed_s"] = elapsed;
        {
            std::lock_guard<std::mutex> lock(mutex);
            results[job.submission][job.stage] = entry;
            seconds[job.submission] += elapsed;
        }
        progress.done(sub.name + ": " + stages[job.stage]);
    });

    std::vector<json> reports;
    for (std::size_t s = 0; s < submissions.size(); ++s) {
        json report = submissionReport(submissions[s], results[s], seconds[s], stages, options);
        writeReports(report, submissions[s], options);
        reports.push_back(report);
    }
    return reports;
}

}  // namespace voxlab
