// voxlab grader: one stage of one implementation in a sandboxed child
// process (see stage_job.h).
//
// What the worker may read is a snapshot made here, in its own work folder:
//   impl/<stage>/   the graded stage, only the manifest's files (and GLSL
//                   helpers beside them) from the submission, each checked
//                   to be a regular file under the size limit;
//   impl/<other>/   the GLSL of the stages the manifest `requires` (and
//                   theirs), from the reference, so that one mistake is
//                   not counted twice; no other stage's code, which could
//                   stand in for the graded one;
//   task/<stage>/   the manifest and its scenes (no expected outputs);
//   lib/build/      the submission's named .cpp files built into a stage
//                   library, by a compiler that reads only the snapshot,
//                   the framework's headers and the system, and writes only
//                   there (temporary files in a size-capped tmpfs);
//   lib/ref/        the reference's C++ stages, copied in after that build.
// Plus shaders/, the datasets and the system. It writes nowhere: its results
// come back through the results channel (worker_results.h). The build and
// the run share one cgroup: one process count and one memory cap for
// everything the stage starts.
#include "stage_job.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "stage_boundary.h"
#include "voxlab/atomic_file.h"
#include "voxlab/child_process.h"
#include "voxlab/error.h"
#include "voxlab/project_root.h"
#include "voxlab/scene.h"
#include "voxlab/stage_library.h"

namespace voxlab::grading {

namespace fs = std::filesystem;

std::string voxlabExecutable(const GraderOptions& options) {
    if (!options.voxlab.empty()) return options.voxlab;
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw Error("cannot find the voxlab executable (/proc/self/exe): " + ec.message());
    return self.string();
}

namespace {

// Reads a submission's file without following links or blocking on FIFOs;
// returns "" or what is wrong with it ("is a link", "is 5 MB, over ...").
std::string readStageFile(const fs::path& path, std::string* bytes) {
    struct stat st;
    if (lstat(path.c_str(), &st) != 0) return "is missing";
    if (S_ISLNK(st.st_mode)) return "is a link: submit the file itself";
    if (!S_ISREG(st.st_mode)) return "is not a regular file";
    if (std::uintmax_t(st.st_size) > kMaxStageFileBytes)
        return "is " + std::to_string(st.st_size) + " bytes, over the limit of " +
               std::to_string(kMaxStageFileBytes) + " bytes for a stage file";
    const int fd = open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return "cannot be read";
    bytes->assign(std::size_t(st.st_size) + 1, '\0');
    std::size_t got = 0;
    for (ssize_t n; got < bytes->size() && (n = read(fd, bytes->data() + got, bytes->size() - got)) > 0;)
        got += std::size_t(n);
    close(fd);
    if (got > kMaxStageFileBytes) return "grew past the size limit while being read";
    bytes->resize(got);
    return "";
}

bool blank(const std::string& text) {
    return std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isspace(c); });
}

// GLSL helper files a stage may include from its own folder, besides its
// manifest's files (never compiled as C++).
bool isHelper(const fs::path& p) {
    const std::string ext = p.extension().string();
    return ext == ".glsl" || ext == ".h" || ext == ".hpp";
}

// Copies the graded stage's files from the submission into impl/<stage>;
// sets outcome.problem when one is missing, empty, a link or too large.
void snapshotGradedStage(const StageRun& run, const StageManifest& manifest, const fs::path& to,
                         RunOutcome& outcome) {
    const fs::path from = fs::path(run.implementationRoot) / run.stage;
    fs::create_directories(to);
    struct stat st;
    if (lstat(from.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
        outcome.problemKind = "error";
        outcome.problem = run.stage + "/ is not a folder (a link?): submit the folder itself";
        return;
    }
    std::vector<std::string> names = manifest.files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(from, ec))
        if (names.size() < manifest.files.size() + 32 && isHelper(entry.path()) &&
            std::find(names.begin(), names.end(), entry.path().filename()) == names.end())
            names.push_back(entry.path().filename());
    for (std::size_t i = 0; i < names.size(); ++i) {
        const bool required = i < manifest.files.size();
        std::string bytes;
        const std::string wrong = readStageFile(from / names[i], &bytes);
        const std::string shown = run.stage + "/" + names[i];
        if (!wrong.empty() && !required) continue;  // a helper that is not fit is not copied
        if (wrong == "is missing" || (wrong.empty() && required && blank(bytes))) {
            if (outcome.problem.empty()) outcome.problem = shown + (wrong.empty() ? " is empty" : " is missing");
            if (outcome.problemKind.empty()) outcome.problemKind = "not_implemented";
            continue;
        }
        if (!wrong.empty()) {
            outcome.problemKind = "error";
            outcome.problem = shown + " " + wrong;
            return;
        }
        writeFileAtomically((to / names[i]).string(), bytes);
    }
}

// From the reference, the GLSL of the stages `stage` requires and of those
// the framework's shaders include (stage_boundary.h says what the graded
// stage may use of them).
void snapshotOtherStages(const std::string& referenceRoot, const std::string& stage, const fs::path& impl) {
    std::vector<std::string> others = requiredStages(referenceRoot, stage);
    for (const std::string& s : frameworkStages(referenceRoot))
        if (s != stage && !std::count(others.begin(), others.end(), s)) others.push_back(s);
    std::error_code ec;
    for (const std::string& other : others) {
        const fs::path folder = fs::path(referenceRoot) / other;
        for (const auto& entry : fs::directory_iterator(folder, ec)) {
            const std::string ext = entry.path().extension().string();
            if (!entry.is_regular_file() || (ext != ".glsl" && ext != ".frag" && ext != ".vert")) continue;
            fs::create_directories(impl / other);
            fs::copy_file(entry.path(), impl / other / entry.path().filename());
        }
    }
}

// The manifest and the scene files it grades, which the worker reads;
// without the hidden scenes unless they are graded.
void copyTask(const std::string& manifestRoot, const StageManifest& manifest, bool hiddenScenes,
              const fs::path& task) {
    const fs::path from = fs::path(manifestRoot) / manifest.stage, to = task / manifest.stage;
    std::ifstream in(from / "grading.json");
    nlohmann::json j = nlohmann::json::parse(in);
    if (!hiddenScenes && j.contains("scenes")) {
        nlohmann::json kept = nlohmann::json::array();
        for (const nlohmann::json& s : j["scenes"])
            if (!s.value("hidden", false)) kept.push_back(s);
        j["scenes"] = kept;
    }
    j.erase("hints");  // the grader's business; they name hidden scenes
    fs::create_directories(to);
    writeFileAtomically((to / "grading.json").string(), j.dump(2) + "\n");
    for (const GradedScene& scene : manifest.scenes) {
        if (scene.hidden && !hiddenScenes) continue;
        const fs::path target = to / fs::relative(scene.scenePath, from);
        fs::create_directories(target.parent_path());
        fs::copy_file(scene.scenePath, target, fs::copy_options::overwrite_existing);
    }
}

ChildLimits sandboxLimits(double seconds, const std::vector<std::string>& readable, const ChildCgroup& cgroup) {
    ChildLimits limits;
    limits.isolate = true;
    limits.seconds = seconds;
    limits.readable = readable;
    limits.cgroup = &cgroup;
    limits.environment["MESA_SHADER_CACHE_DISABLE"] = "true";
    return limits;
}

// The programs the compiler driver runs besides itself, as the files they
// resolve to (the assembler and the linker; cc1plus and collect2 live in
// /usr/libexec, which every child may read).
std::vector<std::string> toolchainPrograms() {
    std::vector<std::string> found;
    std::error_code ec;
    for (const char* name : {"as", "ld", "ld.bfd", "ld.gold", "ld.lld"})
        for (const char* dir : {"/usr/local/bin", "/usr/bin", "/usr/x86_64-linux-gnu/bin", "/usr/aarch64-linux-gnu/bin"}) {
            const fs::path real = fs::canonical(fs::path(dir) / name, ec);
            if (!ec && std::find(found.begin(), found.end(), real.string()) == found.end())
                found.push_back(real.string());
        }
    return found;
}

// Builds `sources` (relative to `root`) into `lib`/stage_library.so, itself
// sandboxed: a compiler can be told to read any file (#include "/etc/...",
// an assembler's .incbin). It reads the snapshot, the framework's headers,
// the stages' contracts (only their include/ folders), the prebuilt exports
// and prelude, and the system's toolchain; it writes
// only `lib`, its temporary files into a size-capped tmpfs there, no file
// over 64 MiB.
bool buildLibrary(const std::vector<std::string>& sources, const std::string& root, const fs::path& lib,
                  const ChildCgroup& cgroup, RunOutcome& outcome) {
    std::vector<std::string> readable = {root, projectRoot() + "/framework/stage_library"};
    for (const std::string& dir : stageIncludeDirs()) readable.push_back(dir);
    if (const std::string exports = stageExportsObject(); !exports.empty()) readable.push_back(exports);
    const std::string prelude = stagePreludeHeader();
    if (!prelude.empty()) readable.insert(readable.end(), {prelude, prelude + ".gch"});
    for (const std::string& program : toolchainPrograms()) readable.push_back(program);
    constexpr double kBuildSeconds = 120.0;
    ChildLimits limits = sandboxLimits(kBuildSeconds, readable, cgroup);
    const fs::path scratch = lib / "tmp";
    fs::create_directories(scratch);
    limits.workingDir = root;
    limits.writable = {lib.string()};
    limits.scratch = scratch.string();
    limits.fileBytes = std::size_t(64) << 20;
    limits.environment["TMPDIR"] = scratch.string();
    const std::string library = (lib / "stage_library.so").string();
    ChildResult built = runChild(stageLibraryBuildCommand(sources, library, prelude), limits);
    // The prelude only saves parsing: files that do not build with it are
    // built as written, and that build's messages are the student's. The
    // two builds share the one time limit.
    if (!built.succeeded() && !prelude.empty() && !built.timedOut && built.seconds < limits.seconds - 1.0) {
        limits.seconds -= built.seconds;
        built = runChild(stageLibraryBuildCommand(sources, library), limits);
    }
    std::error_code ec;
    fs::remove_all(scratch, ec);
    if (built.succeeded()) return true;
    outcome.compiled = false;
    outcome.compileLog = built.output.empty() ? "the C++ compiler " + built.describe(kBuildSeconds) : built.output;
    if (built.outOfMemory || built.signal == SIGXFSZ)
        outcome.compileLog += "\n(the build " + built.describe(kBuildSeconds) +
                              (built.signal == SIGXFSZ ? ": it wrote a file over the 64 MiB limit)" : ")");
    return false;
}

// The .cpp files the stage library is built from (relative to `root`).
std::vector<std::string> cppSources(const StageRun& run, const StageManifest& manifest, const std::string& root) {
    std::vector<std::string> sources;
    auto add = [&](const fs::path& folder, const std::vector<std::string>& only) {
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(folder, ec)) {
            const std::string name = entry.path().filename();
            if (entry.is_regular_file() && entry.path().extension() == ".cpp" &&
                (only.empty() || std::count(only.begin(), only.end(), name)))
                sources.push_back(fs::relative(entry.path(), root).string());
        }
    };
    if (run.graded) {
        std::vector<std::string> named;
        for (const std::string& f : manifest.files)
            if (fs::path(f).extension() == ".cpp") named.push_back(f);
        if (!named.empty()) add(fs::path(root) / run.stage, named);
    } else if (fs::path(root).lexically_normal() != fs::path(projectRoot() + "/reference").lexically_normal()) {
        // A self-check: the student's whole tree, C++ included.
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(root, ec))
            if (entry.is_directory()) add(entry.path(), {});
    }
    std::sort(sources.begin(), sources.end());
    return sources;
}

// What the worker reads besides its task: shaders/ and datasets/ whole, and
// of the stage folders only their shader files (the folders also hold the
// stages' C++, their checks and oracle tests, which a graded stage must not
// read: Landlock allows single files).
std::vector<std::string> dataFolders() {
    std::vector<std::string> folders = {projectRoot() + "/shaders", projectRoot() + "/datasets"};
    std::error_code ec;
    for (const auto& entry : fs::recursive_directory_iterator(stagesRoot(), ec))
        if (entry.is_regular_file(ec) && isShaderFile(entry.path().string())) folders.push_back(entry.path().string());
    const char* path = std::getenv("VOXLAB_DATA_PATH");
    for (std::string rest = path ? path : ""; !rest.empty();) {
        const std::size_t colon = rest.find(':');
        if (!rest.substr(0, colon).empty()) folders.push_back(rest.substr(0, colon));
        rest = colon == std::string::npos ? "" : rest.substr(colon + 1);
    }
    return folders;
}

// The worker's command line, and the libraries it loads: the reference's
// C++ stages (copied in after the submission's build, which never sees
// them), then the submission's.
std::vector<std::string> workerCommand(const StageRun& run, const std::string& root, const fs::path& work,
                                       const GraderOptions& options, bool builtLibrary) {
    std::vector<std::string> worker = {voxlabExecutable(options), "grade-worker", "--stage", run.stage,
                                       "--manifest-root", (work / "task").string(), "--implementation", root};
    const fs::path referenceLibrary = fs::path(options.expectedDir) / "reference_stages.so";
    if (fs::exists(referenceLibrary)) {
        fs::create_directories(work / "lib/ref");
        fs::copy_file(referenceLibrary, work / "lib/ref/reference_stages.so");
        worker.insert(worker.end(), {"--stage-library", (work / "lib/ref/reference_stages.so").string()});
    }
    if (run.graded) worker.push_back("--graded");
    if (builtLibrary) worker.insert(worker.end(), {"--graded-library", (work / "lib/build/stage_library.so").string()});
    return worker;
}

// The worker's limits: it reads its snapshot, task and libraries, the
// shaders and datasets, and runs the stage host; it writes nothing.
ChildLimits workerLimits(const StageRun& run, const std::string& root, const fs::path& work,
                         const GraderOptions& options, const ChildCgroup& cgroup) {
    std::vector<std::string> readable = dataFolders();
    readable.insert(readable.end(), {root, (work / "task").string(), (work / "lib").string()});
    const std::string host = fs::path(voxlabExecutable(options)).parent_path() / "voxlab-stage-host";
    if (fs::exists(host)) readable.push_back(host);
    // A self-check (the student's own tree on their own machine) borrows the
    // stages it lacks from reference/ where there is one; grading never does.
    if (!run.graded) readable.push_back(projectRoot() + "/reference");
    ChildLimits limits = sandboxLimits(options.timeLimit, readable, cgroup);
    limits.memoryBytes = options.memoryLimit;
    limits.fileBytes = std::size_t(256) << 20;  // Mesa keeps large textures in memfds, which this also caps
    limits.resultsBytes = std::size_t(64) << 20;
    limits.workingDir = root;
    if (options.renderThreads > 0) {
        limits.environment["LP_NUM_THREADS"] = std::to_string(options.renderThreads);
    } else if (!std::getenv("LP_NUM_THREADS")) {
        const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
        limits.environment["LP_NUM_THREADS"] = std::to_string(std::max(1u, cores / unsigned(std::max(1, options.jobs))));
    }
    return limits;
}

}  // namespace

RunOutcome runStage(const StageRun& run, const StageManifest& manifest, const GraderOptions& options) {
    RunOutcome outcome;
    const fs::path work = run.workDir;
    fs::remove_all(work);
    fs::create_directories(work / "lib/build");
    copyTask(options.referenceRoot, manifest, options.hiddenScenes, work / "task");
    std::string root = run.implementationRoot;
    if (run.graded) {
        root = (work / "impl").string();
        snapshotGradedStage(run, manifest, work / "impl" / run.stage, outcome);
        if (outcome.problemKind == "error") return outcome;
        snapshotOtherStages(options.referenceRoot, run.stage, work / "impl");
        const std::string crossed = checkStageBoundary(root, run.stage, requiredStages(options.referenceRoot, run.stage),
                                                       options.referenceRoot, projectRoot() + "/shaders");
        if (!crossed.empty()) {
            outcome.compiled = false;
            outcome.compileLog = crossed;
            return outcome;
        }
    }
    outcome.stubs = unimplementedFunctions((fs::path(root) / run.stage).string());
    if (!outcome.problem.empty()) return outcome;

    // One process count and one memory cap for the build and the run.
    const ChildCgroup cgroup(kStageProcesses, options.memoryLimit);
    const std::vector<std::string> sources = cppSources(run, manifest, root);
    if (!sources.empty() && !buildLibrary(sources, root, work / "lib/build", cgroup, outcome)) return outcome;
    const ChildLimits limits = workerLimits(run, root, work, options, cgroup);
    const ChildResult result = runChild(workerCommand(run, root, work, options, !sources.empty()), limits);
    outcome.finished = result.succeeded();
    outcome.ended = result.describe(limits.seconds);
    outcome.output = result.output;
    outcome.sandbox = result.sandbox;
    outcome.results = parseWorkerResults(result.results, manifest);
    if (result.resultsTruncated && outcome.results.problem.empty())
        outcome.results.problem = "the worker sent more than the results channel takes";
    return outcome;
}

}  // namespace voxlab::grading
