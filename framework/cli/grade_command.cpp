// voxlab grade / voxlab check: the grader's command line (see grader.h).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "commands.h"
#include "voxlab/assignment.h"
#include "voxlab/atomic_file.h"
#include "voxlab/grading.h"
#include "voxlab/error.h"
#include "voxlab/expected_cache.h"
#include "voxlab/grader.h"
#include "voxlab/html_report.h"
#include "voxlab/similarity.h"

namespace voxlab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<OptionSpec> limitOptions() {
    return {{"assignment", "FILE", "an assignment file (courses/*.json): its stages, points and test visibility"},
            {"stage", "S", "grade only stage S (repeatable; default: every stage, or the assignment's)"},
            {"out", "DIR", "report folder"},
            {"jobs", "N", "stages graded at once, each in its own process (default: the CPU count)"},
            {"time-limit", "SECONDS", "per stage and submission (default 60)"},
            {"memory-limit", "MIB", "address space per stage process (default 4096)"},
            {"tolerance", "KEY=VALUE", "an image tolerance for every scene, e.g. min_ssim=0.95 (repeatable; keys: docs/instructors.md)"},
            {"quiet", "", "no progress bar"},
            {"no-cache", "", "render the reference's expected outputs even when the cache holds them"},
            {"expected", "DIR", "grade against expected outputs rendered elsewhere (--render-expected), e.g. on another GL"},
            {"help", "", "show this help"}};
}

GraderOptions limitsFrom(const Args& args) {
    GraderOptions o;
    o.stages = args.getAll("stage");
    o.jobs = args.get("jobs") ? parseInt(*args.get("jobs"), "--jobs")
                              : int(std::max(1u, std::thread::hardware_concurrency()));
    if (o.jobs < 1 || o.jobs > 256) throw Error("option --jobs: must be in 1..256");
    if (args.get("time-limit")) o.timeLimit = parseNumber(*args.get("time-limit"), "--time-limit");
    if (!(o.timeLimit > 0 && o.timeLimit <= 86400)) throw Error("option --time-limit: must be in (0, 86400] seconds");
    if (args.get("memory-limit")) {
        const double mib = parseNumber(*args.get("memory-limit"), "--memory-limit");
        if (!(mib >= 256 && mib <= 1 << 20)) throw Error("option --memory-limit: must be in 256..1048576 MiB");
        o.memoryLimit = std::size_t(mib) << 20;
    }
    for (const std::string& kv : args.getAll("tolerance")) {
        const std::size_t eq = kv.find('=');
        if (eq == std::string::npos || eq == 0) throw Error("option --tolerance: expected KEY=VALUE, got '" + kv + "'");
        o.tolerance[kv.substr(0, eq)] = parseNumber(kv.substr(eq + 1), "--tolerance " + kv.substr(0, eq));
    }
    overTolerance({}, o.tolerance, "option --tolerance");  // a wrong key or value stops here, before any grading
    o.progress = !args.has("quiet");
    o.cache = !args.has("no-cache");
    return o;
}

// An assignment file chooses the stages (a --stage must be one of them)
// and their points.
std::optional<Assignment> assignmentFrom(const Args& args, GraderOptions& options) {
    if (!args.get("assignment")) return std::nullopt;
    Assignment a = loadAssignment(*args.get("assignment"), options.referenceRoot);
    std::vector<std::string> stages;
    for (const AssignmentStage& s : a.stages) {
        stages.push_back(s.stage);
        if (s.points) options.points[s.stage] = *s.points;
    }
    for (const std::string& s : options.stages)
        if (std::find(stages.begin(), stages.end(), s) == stages.end())
            throw Error("option --stage: " + s + " is not a stage of " + a.path);
    if (options.stages.empty()) options.stages = stages;
    return a;
}

// --expected DIR: the expected outputs were rendered elsewhere (on another
// GL implementation, or by an instructor for a release) and are used as
// they are; DIR/expected.json says whether they hold the hidden scenes.
void useExpectedFrom(const Args& args, GraderOptions& options) {
    if (!args.get("expected")) return;
    const fs::path dir = *args.get("expected");
    if (!fs::is_directory(dir)) throw Error("option --expected: " + dir.string() + ": no such folder");
    options.shipped = true;
    options.expectedDir = fs::absolute(dir).lexically_normal().string();
    std::ifstream in(dir / "expected.json");
    const json record = json::parse(in, nullptr, false);
    options.hiddenScenes = !record.is_discarded() && record.value("hidden_scenes", false);
}

std::optional<double> timeOption(const Args& args, const std::string& name) {
    if (!args.get(name)) return std::nullopt;
    const std::optional<double> t = parseIsoTime(*args.get(name));
    if (!t) throw Error("option --" + name + ": not an ISO 8601 time (e.g. 2026-12-01T23:59:00+01:00)");
    return t;
}

// A submission as uploaded, brought into the shape of assignments/
// (assignment.h): nested folders are found, loose files are placed.
Submission shapedSubmission(const std::string& name, const fs::path& upload, const fs::path& report,
                            const GraderOptions& options) {
    std::vector<std::string> stages;  // an unknown one is the grader's to report, with its own message
    for (const std::string& s : options.stages.empty() ? gradedStages(options.referenceRoot) : options.stages)
        if (fs::exists(fs::path(options.referenceRoot) / s / "grading.json")) stages.push_back(s);
    const fs::path staging = report / ".upload";
    fs::remove_all(staging);
    Submission s{name, "", report.string(), {}, ""};
    s.folder = submissionRoot(upload.string(), options.referenceRoot, stages, staging.string(), &s.layoutNote);
    return s;
}

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

// One row per submission: total, then each stage's score. The table is
// built in memory and saved atomically: a failed save leaves the previous
// gradebook whole and ends the command with an error.
void writeGradebook(const std::vector<json>& reports, const std::string& path) {
    std::ostringstream csv;
    csv << "name,score,max_score";
    if (!reports.empty())
        for (const json& s : reports[0]["stages"]) csv << "," << csvField(s.value("stage", "?"));
    csv << ",problems\n";
    for (const json& r : reports) {
        char total[64];
        std::snprintf(total, sizeof total, "%.2f,%.2f", r.value("score", 0.0), r.value("max_score", 0.0));
        csv << csvField(r.value("name", "?")) << "," << total;
        for (const json& s : r["stages"]) {
            char score[32];
            std::snprintf(score, sizeof score, "%.2f", s.value("score", 0.0));
            csv << "," << score;
        }
        csv << "," << csvField(problemsSummary(r)) << "\n";  // worst first (html_report.h)
    }
    writeFileAtomically(path, csv.str());
}

// Similar code across the class, as evidence for a person (similarity.h):
// OUT/similarity.json and .html. Returns the line to print.
std::string reportSimilarity(const std::vector<Submission>& submissions, const GraderOptions& options,
                             double threshold, const fs::path& out) {
    std::vector<SimilaritySubmission> code;
    for (const Submission& s : submissions) code.push_back({s.name, s.folder});
    SimilarityOptions o;
    o.threshold = threshold;
    const SimilarityReport r = findSimilarCode(code, similarityStages(options.referenceRoot, options.stages),
                                               projectRoot() + "/assignments", o);
    writeSimilarityReport(r, out.string());
    return std::to_string(r.pairs.size()) + " pair(s) of submissions with similar code, evidence for you to judge: " +
           (out / "similarity.html").string();
}

// --prepare: the expected outputs rendered into the cache (hidden scenes
// included, as grading renders them), the work folder removed.
int prepareCache(const Args& args) {
    const std::optional<std::string> cache = expected_cache::folder();
    if (!cache) throw Error("--prepare: the expected-output cache is off (VOXLAB_EXPECTED_CACHE is empty or 'off')");
    if (args.has("no-cache")) throw Error("--prepare fills the cache: it cannot be used with --no-cache");
    GraderOptions options = limitsFrom(args);
    options.referenceRoot = args.get("reference").value_or(projectRoot() + "/reference");
    const fs::path work = fs::path(*cache) / (".prepare_" + std::to_string(getpid()));
    options.expectedDir = work.string();
    try {
        renderExpectedOutputs(options);
    } catch (...) {
        fs::remove_all(work);
        throw;
    }
    fs::remove_all(work);
    std::cout << *cache << "\n";
    return 0;
}

}  // namespace

int gradeCommand(int argc, char** argv) {
    std::vector<OptionSpec> specs = {
        {"submission", "DIR", "a submission folder, shaped like assignments/"},
        {"batch", "DIR", "grade every submission folder inside DIR (a class)"},
        {"reference", "DIR", "the reference solution (default: the project's reference/)"},
        {"render-expected", "DIR", "only render the reference's expected outputs into DIR (for a student release)"},
        {"with-hidden", "", "--render-expected: also the hidden scenes (for grading with --expected, not for students)"},
        {"prepare", "", "only render the reference's expected outputs into the cache, so that grading starts at once"},
        {"submitted-at", "TIME", "when the submission was made (ISO 8601), for the assignment's late policy"},
        {"due", "TIME", "the due date (ISO 8601), instead of the assignment file's"},
        {"similarity-threshold", "X", "--batch: list pairs whose stage code is this alike (0..1, default 0.5) or off"}};
    for (const OptionSpec& s : limitOptions()) specs.push_back(s);
    const Args args(specs, argc, argv, 2, "grade");
    if (args.get("render-expected") && !args.has("submission") && !args.has("batch")) {
        GraderOptions options = limitsFrom(args);
        options.referenceRoot = args.get("reference").value_or(projectRoot() + "/reference");
        options.expectedDir = *args.get("render-expected");
        // A release's goldens: the hidden scenes stay with the instructor.
        options.hiddenScenes = args.has("with-hidden");
        renderExpectedOutputs(options);
        std::cout << options.expectedDir << "\n";
        return 0;
    }
    if (args.has("prepare")) return prepareCache(args);
    if (args.has("help") || args.has("submission") == args.has("batch")) {
        std::cout << "usage: voxlab grade --submission DIR [--stage S]... [--out REPORT_DIR]\n"
                     "       voxlab grade --batch DIR [--out DIR] [--jobs N]\n\n"
                     "Grades a submission stage by stage against the reference solution: every grading scene\n"
                     "(reference/<stage>/grading.json) is rendered by both and compared (pixel difference, SSIM,\n"
                     "FLIP), and function checks run on random inputs. Each stage runs in its own process with a\n"
                     "time limit and a memory cap. Writes REPORT_DIR/index.html (open it in a browser),\n"
                     "report.json and results.json (Gradescope). --batch grades each folder of DIR into\n"
                     "OUT/<name>/ and writes OUT/gradebook.csv and OUT/index.html, and OUT/similarity.html: pairs\n"
                     "whose stage code is alike, as evidence for you to judge. An upload may be the\n"
                     "assignments/ folder, its contents, a folder with it nested inside, or loose stage files.\n"
                     "--assignment FILE (courses/*.json) chooses the stages, their points, each test's\n"
                     "visibility in results.json and the late policy (with --submitted-at).\n\n"
                  << formatOptions(specs);
        return args.has("help") ? 0 : 2;
    }
    GraderOptions options = limitsFrom(args);
    options.referenceRoot = args.get("reference").value_or(projectRoot() + "/reference");
    const fs::path out = args.get("out").value_or("grade-report");
    options.expectedDir = (out / ".expected").string();
    useExpectedFrom(args, options);
    const std::optional<Assignment> assignment = assignmentFrom(args, options);
    const std::optional<double> submittedAt = timeOption(args, "submitted-at"), due = timeOption(args, "due");
    std::optional<double> similarity = SimilarityOptions().threshold;
    if (args.get("similarity-threshold")) similarity = parseSimilarityThreshold(*args.get("similarity-threshold"));
    if (assignment)
        options.adjustReport = [&](json& report) { applyAssignment(report, *assignment, submittedAt, due); };

    std::vector<Submission> submissions;
    if (args.has("submission")) {
        const fs::path folder = *args.get("submission");
        if (!fs::is_directory(folder)) throw Error(folder.string() + ": no such folder");
        fs::path normal = fs::absolute(folder).lexically_normal();
        if (normal.filename().empty()) normal = normal.parent_path();  // "alice/"
        submissions.push_back(shapedSubmission(normal.filename().string(), folder, out, options));
    } else {
        const fs::path batch = *args.get("batch");
        if (!fs::is_directory(batch)) throw Error(batch.string() + ": no such folder");
        for (const auto& entry : fs::directory_iterator(batch))
            if (entry.is_directory() && entry.path().filename().string()[0] != '.')
                submissions.push_back(shapedSubmission(entry.path().filename().string(), entry.path(),
                                                       out / entry.path().filename(), options));
        std::sort(submissions.begin(), submissions.end(),
                  [](const Submission& a, const Submission& b) { return a.name < b.name; });
        if (submissions.empty()) throw Error(batch.string() + ": no submission folders inside");
    }
    fs::create_directories(out);
    const auto start = std::chrono::steady_clock::now();
    const std::vector<json> reports = gradeSubmissions(submissions, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (args.has("submission")) {
        std::cout << summaryTable(reports[0]) << "report: " << (out / "index.html").string() << "\n";
    } else {
        writeGradebook(reports, (out / "gradebook.csv").string());
        json gradebook = {{"submissions", reports}, {"elapsed_s", seconds}};
        writeClassHtmlReport(gradebook, out.string());
        for (const json& r : reports)
            std::printf("%-24s %7.2f / %g\n", r.value("name", "?").c_str(), r.value("score", 0.0),
                        r.value("max_score", 0.0));
        std::printf("%zu submissions graded in %.1f s; gradebook: %s\n", reports.size(), seconds,
                    (out / "gradebook.csv").string().c_str());
        if (similarity) std::cout << reportSimilarity(submissions, options, *similarity, out) << "\n";
    }
    return 0;
}

int checkCommand(int argc, char** argv) {
    std::vector<OptionSpec> specs = {{"submission", "DIR", "the tree to check (default: the project's assignments/)"}};
    for (const OptionSpec& s : limitOptions()) specs.push_back(s);
    const Args args(specs, argc, argv, 2, "check");
    if (args.has("help")) {
        std::cout << "usage: voxlab check [--stage S]... [--out DIR]\n\n"
                     "Checks your work in assignments/ the way the grader will: every grading scene of each\n"
                     "stage is rendered with your code and compared with the expected image (shipped in\n"
                     "expected/ with a student release, else rendered from reference/). Prints a table and\n"
                     "writes DIR/index.html (default voxlab-check/) with your image, the expected one and a\n"
                     "heat map of the differences for every scene. Exit status 0 when every stage checked passes.\n\n"
                  << formatOptions(specs);
        return 0;
    }
    GraderOptions options = limitsFrom(args);
    options.isolateStage = false;
    options.hiddenScenes = false;
    const fs::path root = projectRoot();
    const fs::path out = args.get("out").value_or("voxlab-check");
    const std::string tree = args.get("submission").value_or((root / "assignments").string());
    if (fs::is_directory(root / "expected")) {
        options.shipped = true;
        options.referenceRoot = tree;
        options.expectedDir = (root / "expected").string();
    } else {
        options.referenceRoot = (root / "reference").string();
        options.expectedDir = (out / ".expected").string();
    }
    useExpectedFrom(args, options);
    assignmentFrom(args, options);  // its stages and points, checked against the manifests just chosen
    fs::create_directories(out);
    const std::vector<json> reports = gradeSubmissions({{"your work", tree, out.string()}}, options);
    std::cout << summaryTable(reports[0]) << "report: " << (out / "index.html").string() << "\n";
    for (const json& s : reports[0]["stages"])
        if (s.value("status", "") != "passed" && s.value("status", "") != "example") return 1;
    return 0;
}

}  // namespace voxlab::cli
