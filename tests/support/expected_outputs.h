// Test support for the grader's end-to-end tests: the reference's expected
// outputs, rendered once per test file.
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <filesystem>
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

// A test suite that grades against the reference: its expected outputs are
// rendered once, into Derived::expectedFolder() with Derived::options(), and
// a failure to render them fails every test of the suite.
template <class Derived>
class ExpectedOutputsSuite : public ::testing::Test {
public:
    static void SetUpTestSuite() {
        expected_ = Derived::expectedFolder();
        setUpError_ = renderExpectedOrWhy(Derived::options());
    }
    void SetUp() override {
        if (!setUpError_.empty()) FAIL() << "rendering the expected outputs failed: " << setUpError_;
    }
    // Grading as a student release ships it (the goldens), one llvmpipe
    // thread per stage, no progress bar; a suite adds its own settings.
    static GraderOptions referenceOptions() {
        GraderOptions o;
        o.voxlab = VOXLAB_BINARY;
        o.referenceRoot = (std::filesystem::path(VOXLAB_SOURCE_DIR) / "reference").string();
        o.expectedDir = expected_.string();
        o.shipped = true;
        o.renderThreads = 1;
        o.progress = false;
        return o;
    }

private:
    static inline std::filesystem::path expected_;
    static inline std::string setUpError_;
};

}  // namespace voxlab::testing
