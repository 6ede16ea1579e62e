// voxlab grade / voxlab check: the grader's command line (see grader.h).
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <set>
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
#include "voxlab/untrusted_text.h"
#include "voxlab/upload.h"

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

// The grader's copies of the uploads (upload.h): a private folder in OUT,
// made with mkdtemp and removed when the command ends, however it ends.
class UploadCopies {
public:
    explicit UploadCopies(const fs::path& out) {
        fs::create_directories(out);
        std::string pattern = (out / ".uploads-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw Error(terminalLine(out.string()) + ": cannot create a folder for the uploads' copies");
        path_ = pattern;
    }
    UploadCopies(const UploadCopies&) = delete;
    UploadCopies& operator=(const UploadCopies&) = delete;
    ~UploadCopies() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

bool isZipFile(const fs::path& p) {
    std::string ext = p.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    std::error_code ec;
    return ext == ".zip" && fs::is_regular_file(p, ec);
}

// A student's name from their upload: the folder's name, or the zip's without ".zip".
std::string uploadName(const fs::path& upload) {
    fs::path normal = fs::absolute(upload).lexically_normal();
    if (normal.filename().empty()) normal = normal.parent_path();  // "alice/"
    return isZipFile(normal) ? normal.stem().string() : normal.filename().string();
}

// The uploads of a class: every folder and .zip file directly in `batch`
// (names starting with a dot are skipped), sorted by name. Anything else
// is named on stderr and skipped.
std::vector<fs::path> classUploads(const fs::path& batch) {
    std::vector<fs::path> uploads;
    std::error_code ec;
    for (fs::directory_iterator it(batch, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path p = it->path();
        if (p.filename().string()[0] == '.') continue;
        std::error_code typeError;
        if (it->is_directory(typeError) || isZipFile(p)) uploads.push_back(p);
        else std::cerr << "voxlab grade: skipped " << terminalLine(p.filename().string(), 200)
                       << ": not a folder or a .zip file\n";
    }
    if (ec) throw Error(terminalLine(batch.string()) + ": cannot list the class folder: " + ec.message());
    std::sort(uploads.begin(), uploads.end(),
              [](const fs::path& a, const fs::path& b) { return uploadName(a) < uploadName(b); });
    return uploads;
}

// The class's gradebook entries for OUT/index.html: each links to its
// submission's own folder.
json classGradebook(const std::vector<json>& reports, const std::vector<Submission>& submissions, double seconds) {
    json entries = json::array();
    for (std::size_t i = 0; i < reports.size(); ++i) {
        json entry = reports[i];
        entry["report"] = fs::path(submissions[i].reportDir).filename().string() + "/index.html";
        entries.push_back(entry);
    }
    return {{"submissions", entries}, {"elapsed_s", seconds}};
}

// Similar code across the class, as evidence for a person (similarity.h):
// OUT/similarity.json and .html. Returns the line to print.
std::string reportSimilarity(const std::vector<Submission>& submissions, const GraderOptions& options,
                             double threshold, const fs::path& out) {
    std::vector<SimilaritySubmission> code;
    for (const Submission& s : submissions)
        if (s.problem.empty()) code.push_back({s.name, s.folder});
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

// --submission: one upload (a folder or a .zip file) graded into `out`. An
// upload that cannot be graded still gets its report, and exit status 1.
int gradeOne(const fs::path& upload, const fs::path& out, const GraderOptions& options) {
    std::error_code ec;
    if (!fs::is_directory(upload, ec) && !isZipFile(upload))
        throw Error(terminalLine(upload.string()) + ": no such folder or .zip file");
    const UploadCopies copies(out);
    std::set<std::string> taken;
    const std::string name = uploadName(upload);
    const Submission submission =
        prepareSubmission(name, upload.string(), out.string(), (copies.path() / safeFolderName(name, taken)).string(),
                          options);
    const std::vector<json> reports = gradeSubmissions({submission}, options);
    std::cout << terminalText(summaryTable(reports[0]), kMaxLogBytes) << "report: " << terminalLine((out / "index.html").string())
              << "\n";
    if (reports[0].value("status", "") != "error") return 0;
    std::cerr << "voxlab grade: " << terminalLine(reports[0].value("name", "?")) << " was not graded: "
              << terminalLine(reports[0].value("message", "")) << "\n";
    return 1;
}

// --batch: every upload in `batch` graded into OUT/<folder>/ (a safe,
// unique folder name: untrusted_text.h), then the gradebook, the class
// report and the similarity report. A submission that cannot be graded is
// a row with its reason; the class is always graded to the end.
int gradeClass(const fs::path& batch, const fs::path& out, const GraderOptions& options,
               std::optional<double> similarity) {
    std::error_code ec;
    if (!fs::is_directory(batch, ec)) throw Error(terminalLine(batch.string()) + ": no such folder");
    const std::vector<fs::path> uploads = classUploads(batch);
    if (uploads.empty()) throw Error(terminalLine(batch.string()) + ": no submission folders or .zip files inside");
    const UploadCopies copies(out);
    std::set<std::string> taken;
    std::vector<Submission> submissions;
    for (const fs::path& upload : uploads) {
        const std::string name = uploadName(upload), folder = safeFolderName(name, taken);
        submissions.push_back(prepareSubmission(name, upload.string(), (out / folder).string(),
                                                (copies.path() / folder).string(), options));
    }
    const auto start = std::chrono::steady_clock::now();
    const std::vector<json> reports = gradeSubmissions(submissions, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeFileAtomically((out / "gradebook.csv").string(), gradebookCsv(reports));
    // The similarity report first, so that the class page links it.
    json gradebook = classGradebook(reports, submissions, seconds);
    std::string similarityLine;
    if (!similarity) {
        gradebook["similarity"] = {{"off", true}};
    } else {
        try {
            similarityLine = reportSimilarity(submissions, options, *similarity, out);
            gradebook["similarity"] = {{"page", "similarity.html"}, {"summary", similarityLine.substr(0, similarityLine.find(" of submissions")) + " listed"}};
        } catch (const std::exception& e) {
            gradebook["similarity"] = {{"error", safeText(e.what())}};
            std::cerr << "voxlab grade: no similarity report: " << terminalLine(e.what()) << "\n";
        }
    }
    writeClassHtmlReport(gradebook, out.string());
    for (const json& r : reports) {
        const std::string status = r.value("status", "") == "error" ? "  not graded: " + r.value("message", "") : "";
        std::printf("%-24s %7.2f / %g%s\n", terminalLine(r.value("name", "?"), 200).c_str(), r.value("score", 0.0),
                    r.value("max_score", 0.0), terminalLine(status, 300).c_str());
    }
    std::printf("%zu submissions graded in %.1f s; gradebook: %s\n", reports.size(), seconds,
                terminalLine((out / "gradebook.csv").string()).c_str());
    if (!similarityLine.empty()) std::cout << terminalLine(similarityLine) << "\n";
    return 0;
}

}  // namespace

int gradeCommand(int argc, char** argv) {
    std::vector<OptionSpec> specs = {
        {"submission", "DIR", "a submission: a folder, shaped like assignments/, or a .zip file"},
        {"batch", "DIR", "grade every submission folder and .zip file inside DIR (a class)"},
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
    if (auto status = usageExit(args, args.has("submission") == args.has("batch"),
                                "usage: voxlab grade --submission DIR|FILE.zip [--stage S]... [--out REPORT_DIR]\n"
                                "       voxlab grade --batch DIR [--out DIR] [--jobs N]\n\n"
                                "Grades a submission stage by stage against the reference solution: every grading scene\n"
                                "(reference/<stage>/grading.json) is rendered by both and compared (pixel difference, SSIM,\n"
                                "FLIP), and function checks run on random inputs. Each stage runs in its own process with a\n"
                                "time limit and a memory cap. Writes REPORT_DIR/index.html (open it in a browser),\n"
                                "report.json and results.json (Gradescope). --batch grades each folder and .zip file of DIR\n"
                                "into OUT/<name>/ (a name that is not a safe folder name gets one) and writes\n"
                                "OUT/gradebook.csv, OUT/index.html, and OUT/similarity.html: pairs whose stage code is\n"
                                "alike, as evidence for you to judge. An upload may be the assignments/ folder, its\n"
                                "contents, a folder with it nested inside, loose stage files, or a zip of any of these;\n"
                                "it is copied once before grading (links and special files are left out). One that\n"
                                "cannot be graded gets a report and a gradebook row saying why.\n"
                                "--assignment FILE (courses/*.json) chooses the stages, their points, each test's\n"
                                "visibility in results.json and the late policy (with --submitted-at).\n\n",
                                specs))
        return *status;
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

    if (args.has("submission")) return gradeOne(*args.get("submission"), out, options);
    return gradeClass(*args.get("batch"), out, options, similarity);
}

int checkCommand(int argc, char** argv) {
    std::vector<OptionSpec> specs = {{"submission", "DIR", "the tree to check (default: the project's assignments/)"}};
    for (const OptionSpec& s : limitOptions()) specs.push_back(s);
    const Args args(specs, argc, argv, 2, "check");
    if (auto status = usageExit(args, false,
                                "usage: voxlab check [--stage S]... [--out DIR]\n\n"
                                "Checks your work in assignments/ the way the grader will: every grading scene of each\n"
                                "stage is rendered with your code and compared with the expected image (shipped in\n"
                                "expected/ with a student release, else rendered from reference/). Prints a table and\n"
                                "writes DIR/index.html (default voxlab-check/) with your image, the expected one and a\n"
                                "heat map of the differences for every scene. Exit status 0 when every stage checked passes.\n\n",
                                specs))
        return *status;
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
