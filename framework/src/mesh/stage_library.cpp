// voxlab: the C++ stage table and stage libraries (see stage_library.h).
#include "voxlab/stage_library.h"
#include "voxlab/project_root.h"

#include <dlfcn.h>
#include <sys/stat.h>

#include "voxlab/error.h"
#include "voxlab/marching_cubes.h"
#include "voxlab/proxy_geometry.h"

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

void loopCubeCases(const double* values, std::size_t count, double isovalue, int* cases) {
    for (std::size_t i = 0; i < count; ++i) cases[i] = table().cubeCase(values + 8 * i, isovalue);
}

void loopEdgeCrossings(const EdgeCrossingCall* calls, std::size_t count, double isovalue, glm::dvec3* points) {
    for (std::size_t i = 0; i < count; ++i)
        points[i] = table().edgeCrossing(calls[i].a, calls[i].b, calls[i].va, calls[i].vb, isovalue);
}

StageBatches& batches() {
    static StageBatches b{&loopCubeCases, &loopEdgeCrossings};
    return b;
}

}  // namespace

const StageBatches& stageBatches() { return batches(); }

void overrideStageBatches(const StageBatches& offered) {
    if (offered.cubeCases) batches().cubeCases = offered.cubeCases;
    if (offered.edgeCrossings) batches().edgeCrossings = offered.edgeCrossings;
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

// The flags are also framework/CMakeLists.txt's for the exports object and
// the prelude: a precompiled header built with others is not used.
std::vector<std::string> stageLibraryBuildCommand(const std::vector<std::string>& sources,
                                                  const std::string& output, const std::string& prelude) {
    std::vector<std::string> cmd = {VOXLAB_CXX_COMPILER, "-std=c++17", "-O1", "-fPIC", "-shared",
                                    "-Wl,-Bsymbolic", "-DGLM_FORCE_CXX17",
                                    "-I" + projectRoot() + "/framework/include"};
    if (!prelude.empty()) cmd.insert(cmd.end(), {"-include", prelude});
    cmd.insert(cmd.end(), sources.begin(), sources.end());
    const std::string exports = stageExportsObject();
    cmd.push_back(exports.empty() ? projectRoot() + "/framework/stage_library/stage_exports.cpp" : exports);
    cmd.push_back("-o");
    cmd.push_back(output);
    return cmd;
}

}  // namespace voxlab
