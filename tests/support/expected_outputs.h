// Test support for the grader's end-to-end tests: the reference's expected
// outputs, rendered once per test file.
#pragma once

#include <exception>
#include <string>

#include "voxlab/grader.h"

namespace voxlab::testing {

// Renders the expected outputs with `options` (shipped or not); returns ""
// or why it failed. A fixture keeps the reason and fails every test with it
// in SetUp(): an exception out of SetUpTestSuite() makes gtest report the
// tests as skipped, which CTest counts as no failure.
inline std::string renderExpectedOrWhy(GraderOptions options) {
    options.shipped = false;
    try {
        renderExpectedOutputs(options);
        return "";
    } catch (const std::exception& e) {
        return e.what();
    }
}

}  // namespace voxlab::testing
