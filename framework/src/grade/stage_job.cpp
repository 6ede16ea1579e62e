// voxlab grader: one stage of one implementation in a child process.
#include "stage_job.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "voxlab/child_process.h"
#include "voxlab/error.h"
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

// A submission's file larger than this is not copied (it is no shader).
constexpr std::uintmax_t kMaxSourceBytes = 4u << 20;

void copyStageFolder(const fs::path& from, const fs::path& to) {
    fs::create_directories(to);
    for (const auto& entry : fs::recursive_directory_iterator(from, fs::directory_options::skip_permission_denied)) {
        const fs::path target = to / fs::relative(entry.path(), from);
        if (entry.is_directory()) fs::create_directories(target);
        else if (entry.is_regular_file() && entry.file_size() <= kMaxSourceBytes)
            fs::copy_file(entry.path(), target, fs::copy_options::overwrite_existing);
    }
}

std::vector<std::string> cppFiles(const fs::path& folder, const fs::path& relativeTo) {
    std::vector<std::string> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec))
        if (entry.is_regular_file() && entry.path().extension() == ".cpp")
            files.push_back(fs::relative(entry.path(), relativeTo).string());
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace

RunOutcome runStage(const StageRun& run, const GraderOptions& options) {
    RunOutcome outcome;
    fs::create_directories(run.outputDir);
    fs::create_directories(run.workDir);
    // The implementation as the worker will see it.
    std::string root = run.implementationRoot;
    std::vector<std::string> sources;
    if (options.isolateStage) {
        root = (fs::path(run.workDir) / "impl").string();
        fs::remove_all(root);
        copyStageFolder(fs::path(run.implementationRoot) / run.stage, fs::path(root) / run.stage);
        sources = cppFiles(fs::path(root) / run.stage, root);
    } else if (options.shipped ||
               fs::path(root).lexically_normal() != fs::path(options.referenceRoot).lexically_normal()) {
        // A self-check: the student's whole tree, C++ included.
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(root, ec))
            if (entry.is_directory())
                for (const std::string& f : cppFiles(entry.path(), root)) sources.push_back(f);
    }

    std::vector<std::string> worker = {voxlabExecutable(options), "grade-worker", "--stage", run.stage,
                                       "--manifest-root", options.referenceRoot, "--implementation", root,
                                       "--out", run.outputDir, "--suffix", run.suffix};
    // Grading: the reference's C++ stages first (stage_library.so next to the
    // expected outputs), then the submission's on top.
    const fs::path referenceLibrary = fs::path(options.expectedDir) / "reference_stages.so";
    if (fs::exists(referenceLibrary)) {
        worker.push_back("--stage-library");
        worker.push_back(referenceLibrary.string());
    }
    if (!sources.empty()) {
        const std::string library = (fs::path(run.workDir) / "stage_library.so").string();
        ChildLimits limits;
        limits.seconds = 120.0;
        limits.workingDir = root;
        limits.writable = {run.workDir};
        limits.environment = {{"TMPDIR", run.workDir}};
        const ChildResult built = runChild(stageLibraryBuildCommand(sources, library), limits);
        if (!built.succeeded()) {
            outcome.compiled = false;
            outcome.compileLog = built.output.empty() ? "the C++ compiler " + built.describe(limits.seconds)
                                                      : built.output;
            return outcome;
        }
        worker.push_back("--stage-library");
        worker.push_back(library);
    }

    ChildLimits limits;
    limits.seconds = options.timeLimit;
    limits.memoryBytes = options.memoryLimit;
    limits.fileBytes = std::size_t(256) << 20;
    limits.workingDir = run.outputDir;
    limits.writable = {run.outputDir};
    limits.environment["MESA_SHADER_CACHE_DISABLE"] = "true";
    if (options.renderThreads > 0) {
        limits.environment["LP_NUM_THREADS"] = std::to_string(options.renderThreads);
    } else if (!std::getenv("LP_NUM_THREADS")) {
        const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
        limits.environment["LP_NUM_THREADS"] = std::to_string(std::max(1u, cores / unsigned(std::max(1, options.jobs))));
    }
    const ChildResult result = runChild(worker, limits);
    outcome.finished = result.succeeded();
    outcome.ended = result.describe(limits.seconds);
    outcome.output = result.output;
    return outcome;
}

}  // namespace voxlab::grading
