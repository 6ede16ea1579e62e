// Test support: the message of the voxlab::Error a callable throws.
#pragma once

#include <string>

#include "voxlab/error.h"

namespace voxlab::testing {

// Runs f and returns the voxlab::Error message it throws ("" if none).
template <class F>
std::string errorOf(F f) {
    try {
        f();
    } catch (const voxlab::Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace voxlab::testing
