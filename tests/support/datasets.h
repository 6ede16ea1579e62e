// Test support: the bundled datasets, and test volumes by name.
#pragma once

#include <string>

#include "voxlab/volume.h"

namespace voxlab::testing {

// A bundled dataset's path (datasets/NAME in the source tree).
inline std::string datasetPath(const std::string& name) {
    return std::string(VOXLAB_SOURCE_DIR) + "/datasets/" + name;
}

// "phantom:SPEC" (makePhantom) or a bundled dataset's file name.
inline Volume namedVolume(const std::string& name) {
    if (name.rfind("phantom:", 0) == 0) return makePhantom(name);
    return loadVolume(datasetPath(name));
}

}  // namespace voxlab::testing
