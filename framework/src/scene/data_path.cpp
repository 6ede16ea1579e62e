// voxlab: finding data files (datasets, transfer functions) and the project
// root. The search order is documented in scene.h.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "voxlab/error.h"
#include "voxlab/scene.h"

namespace voxlab {

namespace fs = std::filesystem;

namespace {

std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? v : "";
}

bool exists(const std::string& path) {
    std::error_code ec;
    return fs::exists(path, ec);
}

}  // namespace

std::string resolveDataPath(const std::string& name, const std::string& baseDir) {
    if (name.rfind("phantom:", 0) == 0) return name;
    if (name.empty()) throw Error("empty data file name");

    // Candidates in order; an absolute name is only ever itself.
    std::vector<std::string> searched{name};
    if (!fs::path(name).is_absolute()) {
        if (!baseDir.empty()) searched.push_back((fs::path(baseDir) / name).string());
        const std::string dataPath = env("VOXLAB_DATA_PATH");
        size_t start = 0;
        while (start <= dataPath.size()) {
            size_t end = dataPath.find(':', start);
            if (end == std::string::npos) end = dataPath.size();
            const std::string dir = dataPath.substr(start, end - start);
            if (!dir.empty()) searched.push_back((fs::path(dir) / name).string());
            start = end + 1;
        }
        searched.push_back((fs::path(projectRoot()) / "datasets" / name).string());
    }

    for (const std::string& candidate : searched)
        if (exists(candidate)) return candidate;

    std::string list;
    for (const std::string& candidate : searched) list += (list.empty() ? "" : ", ") + candidate;
    throw Error(name + ": no such file (searched: " + list + ")");
}

}  // namespace voxlab
