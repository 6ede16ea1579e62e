// voxlab: the C++ stage table and stage libraries (see stage_library.h).
#include "voxlab/stage_library.h"
#include "voxlab/project_root.h"

#include <dlfcn.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>

#include "voxlab/error.h"

namespace voxlab {

namespace {

CppStages& table() {
    static CppStages stages = [] {
        CppStages t;
#define VOXLAB_STAGE_LINKED(name, Result, Parameters) t.name = &name;
        VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_LINKED)
#undef VOXLAB_STAGE_LINKED
        return t;
    }();
    return stages;
}

// Visits each of the table's functions: its name, the same member of a
// second table, and a stub with its signature that says it is not
// implemented.
template <class Visit>
void forEachStageFunction(CppStages& t, const CppStages& other, Visit visit) {
#define VOXLAB_STAGE_VISIT(name, Result, Parameters) \
    visit(#name, t.name, other.name, static_cast<Result(*) Parameters>([] Parameters -> Result { throw NotImplemented(#name); }));
    VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_VISIT)
#undef VOXLAB_STAGE_VISIT
}

}  // namespace

const CppStages& cppStages() { return table(); }

namespace {

// The batch that calls the table's function (Member) once per call.
template <class F>
struct LoopBatch;
template <class R, class... A>
struct LoopBatch<R(A...)> {
    template <R (*CppStages::*Member)(A...)>
    static void run(const std::tuple<A...>* calls, std::size_t count, R* results) {
        for (std::size_t i = 0; i < count; ++i) results[i] = std::apply(table().*Member, calls[i]);
    }
};

CppStageBatches& batches() {
    static CppStageBatches b = [] {
        CppStageBatches loops;
#define VOXLAB_STAGE_LOOP(name, Result, Parameters) \
    loops.name.run = &LoopBatch<Result Parameters>::run<&CppStages::name>;
        VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_LOOP)
#undef VOXLAB_STAGE_LOOP
        return loops;
    }();
    return b;
}

}  // namespace

const CppStageBatches& stageBatches() { return batches(); }

void overrideStageBatches(const CppStageBatches& offered) {
#define VOXLAB_STAGE_OVERRIDE(name, Result, Parameters) \
    if (offered.name.run) batches().name.run = offered.name.run;
    VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_OVERRIDE)
#undef VOXLAB_STAGE_OVERRIDE
}

bool isStageFunction(const std::string& name) {
    bool found = false;
    forEachStageFunction(table(), table(), [&](const char* n, auto&, auto, auto) { found = found || name == n; });
    return found;
}

void clearStageFunctions(const std::vector<std::string>& names) {
    for (const std::string& name : names) {
        bool cleared = false;
        forEachStageFunction(table(), table(), [&](const char* n, auto& function, auto, auto stub) {
            if (name == n) function = stub, cleared = true;
        });
        if (!cleared) throw Error("'" + name + "' is not a C++ stage function");
    }
}

std::vector<std::string> loadStageLibrary(const std::string& path) {
    // RTLD_LOCAL: the library's symbols must not replace anything else's.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = dlerror();
        throw Error(path + ": cannot load the stage library: " + (why ? why : "unknown error"));
    }
    using Getter = CppStages (*)();
    auto get = reinterpret_cast<Getter>(dlsym(handle, "voxlab_stage_library_functions"));
    if (!get) throw Error(path + ": not a voxlab stage library (no voxlab_stage_library_functions)");
    return overrideStageFunctions(get());  // the handle stays open for the life of the process
}

std::vector<std::string> overrideStageFunctions(const CppStages& found) {
    std::vector<std::string> names;
    forEachStageFunction(table(), found, [&](const char* n, auto& function, auto offered, auto) {
        if (!offered) return;
        function = offered;
        names.push_back(n);
    });
    return names;
}

namespace {

bool regularFileExists(const std::string& path) {
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

// An installed tree keeps what the build made in
// share/voxlab/framework/stage_library/ (framework/CMakeLists.txt's
// install rules); a build keeps it in its build folder, at a path fixed at
// build time, while it is still there. The installed copy comes first.
std::string prebuilt(const std::string& installedName, const char* builtPath) {
    const std::string installed = projectRoot() + "/framework/stage_library/" + installedName;
    if (regularFileExists(installed)) return installed;
    if (builtPath && regularFileExists(builtPath)) return builtPath;
    return "";
}

}  // namespace

// Builds without them (the browser's, the fuzzers') have no build paths.
#ifndef VOXLAB_STAGE_CONTRACTS_DIR
#define VOXLAB_STAGE_CONTRACTS_DIR nullptr
#endif
#ifndef VOXLAB_STAGE_EXPORTS_OBJECT
#define VOXLAB_STAGE_EXPORTS_OBJECT nullptr
#endif
#ifndef VOXLAB_STAGE_PRELUDE
#define VOXLAB_STAGE_PRELUDE nullptr
#endif

std::string stageExportsObject() { return prebuilt("stage_exports.o", VOXLAB_STAGE_EXPORTS_OBJECT); }

// The prelude is used only with its precompiled form beside it.
std::string stagePreludeHeader() {
    const std::string header = prebuilt("prelude/voxlab_stage_prelude.h", VOXLAB_STAGE_PRELUDE);
    return !header.empty() && regularFileExists(header + ".gch") ? header : "";
}

namespace {

// The folder of the generated voxlab/stage_contracts.h when the mesh
// module's headers lack it, or "".
std::string stageContractsDir() {
    if (regularFileExists(projectRoot() + "/framework/include/mesh/voxlab/stage_contracts.h")) return "";  // installed
    const char* built = VOXLAB_STAGE_CONTRACTS_DIR;
    return built && regularFileExists(std::string(built) + "/voxlab/stage_contracts.h") ? built : "";
}

}  // namespace

std::vector<std::string> stageIncludeDirs() {
    // The folders of `root` that hold a folder `inside`, in name order.
    const auto holding = [](const std::string& root, const std::string& inside) {
        std::vector<std::string> found;
        std::error_code ec;
        for (const auto& entry : std::filesystem::directory_iterator(root, ec))
            if (std::filesystem::is_directory(entry.path() / inside, ec)) found.push_back(entry.path().string());
        std::sort(found.begin(), found.end());
        return found;
    };
    std::vector<std::string> dirs = holding(projectRoot() + "/framework/include", "voxlab");  // the modules'
    for (const std::string& stage : holding(projectRoot() + "/framework/stages", "include"))  // the contracts
        dirs.push_back(stage + "/include");
    if (const std::string generated = stageContractsDir(); stageExportsObject().empty() && !generated.empty())
        dirs.push_back(generated);
    return dirs;
}

// The flags are also framework/CMakeLists.txt's for the exports object and
// the prelude: a precompiled header built with others is not used.
std::vector<std::string> stageLibraryBuildCommand(const std::vector<std::string>& sources,
                                                  const std::string& output, const std::string& prelude) {
    std::vector<std::string> cmd = {VOXLAB_CXX_COMPILER, "-std=c++17", "-O1", "-fPIC", "-shared",
                                    "-Wl,-Bsymbolic", "-DGLM_FORCE_CXX17"};
    for (const std::string& dir : stageIncludeDirs()) cmd.push_back("-I" + dir);
    const std::string exports = stageExportsObject();
    if (!prelude.empty()) cmd.insert(cmd.end(), {"-include", prelude});
    cmd.insert(cmd.end(), sources.begin(), sources.end());
    cmd.push_back(exports.empty() ? projectRoot() + "/framework/stage_library/stage_exports.cpp" : exports);
    cmd.push_back("-o");
    cmd.push_back(output);
    return cmd;
}

}  // namespace voxlab
