// voxlab: the C++ stage table and stage libraries (see stage_library.h).
#include "voxlab/stage_library.h"

#include <dlfcn.h>

#include "voxlab/error.h"
#include "voxlab/proxy_geometry.h"

namespace voxlab {

namespace {

CppStages& table() {
    static CppStages stages{&planeBoxPolygon, &chooseSliceAxis};
    return stages;
}

}  // namespace

const CppStages& cppStages() { return table(); }

bool isStageFunction(const std::string& name) { return name == "planeBoxPolygon" || name == "chooseSliceAxis"; }

void clearStageFunctions(const std::vector<std::string>& names) {
    for (const std::string& name : names) {
        if (name == "planeBoxPolygon")
            table().planeBoxPolygon = [](glm::dvec3, double, glm::dvec3, glm::dvec3) -> std::vector<glm::dvec3> {
                throw NotImplemented("planeBoxPolygon");
            };
        else if (name == "chooseSliceAxis")
            table().chooseSliceAxis = [](glm::dvec3) -> int { throw NotImplemented("chooseSliceAxis"); };
        else
            throw Error("'" + name + "' is not a C++ stage function");
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
    if (found.planeBoxPolygon) {
        table().planeBoxPolygon = found.planeBoxPolygon;
        names.push_back("planeBoxPolygon");
    }
    if (found.chooseSliceAxis) {
        table().chooseSliceAxis = found.chooseSliceAxis;
        names.push_back("chooseSliceAxis");
    }
    return names;
}

std::vector<std::string> stageLibraryBuildCommand(const std::vector<std::string>& sources,
                                                  const std::string& output) {
    std::vector<std::string> cmd = {VOXLAB_CXX_COMPILER, "-std=c++17", "-O1", "-fPIC", "-shared",
                                    "-Wl,-Bsymbolic", "-DGLM_FORCE_CXX17",
                                    "-I" VOXLAB_SOURCE_DIR "/framework/include"};
    cmd.insert(cmd.end(), sources.begin(), sources.end());
    cmd.push_back(VOXLAB_SOURCE_DIR "/framework/stage_library/stage_exports.cpp");
    cmd.push_back("-o");
    cmd.push_back(output);
    return cmd;
}

}  // namespace voxlab
