// The expected-output cache's key (voxlab/expected_cache.h) must change with
// any change to what the expected images are made from, or a grading run
// would score students against images of an older reference. The oracle is
// the inputs themselves: a copy of reference/ and of a program file, each
// changed in one byte, two bytes swapped, a file renamed, added or emptied,
// and changed back.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "voxlab/expected_cache.h"
#include "support/run_command.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

class ExpectedCacheKey : public ::testing::Test {
protected:
    void SetUp() override {
        root_ = fs::path(::testing::TempDir()) / ("voxlab_cache_key_" + std::to_string(getpid()));
        fs::remove_all(root_);
        fs::create_directories(root_);
        fs::copy(fs::path(VOXLAB_SOURCE_DIR) / "reference", root_ / "reference", fs::copy_options::recursive);
        std::ofstream(root_ / "worker", std::ios::binary) << std::string(300000, 'w') << "end";
    }
    void TearDown() override { fs::remove_all(root_); }
    std::string key() const { return expected_cache::key((root_ / "worker").string(), (root_ / "reference").string()); }
    // Replaces the byte at `at` of `file`, returning the old one.
    static char poke(const fs::path& file, std::size_t at, char value) {
        std::string text = readFile(file.string());
        const char old = text.at(at);
        text[at] = value;
        std::ofstream(file, std::ios::binary) << text;
        return old;
    }
    fs::path root_;
};

TEST_F(ExpectedCacheKey, ChangesWithEveryInputAndOnlyWithIt) {
    const std::string original = key();
    EXPECT_EQ(original.size(), 32u);
    EXPECT_EQ(key(), original) << "the same inputs must give the same key";

    const fs::path scene = root_ / "reference/mip/grading.json";
    const std::size_t middle = fs::file_size(scene) / 2;
    const char old = poke(scene, middle, 'Z');
    EXPECT_NE(key(), original) << "one byte of a manifest";
    poke(scene, middle, old);
    EXPECT_EQ(key(), original) << "changed back";

    // Two neighbouring bytes swapped: same size, same bytes, other order.
    const fs::path glsl = root_ / "reference/mip/mip.glsl";
    std::string text = readFile(glsl.string());
    const std::string kept = text;
    std::size_t at = text.size() / 2;
    while (text[at] == text[at + 1]) ++at;
    std::swap(text[at], text[at + 1]);
    std::ofstream(glsl, std::ios::binary) << text;
    EXPECT_NE(key(), original) << "two bytes swapped";
    std::ofstream(glsl, std::ios::binary) << kept;
    EXPECT_EQ(key(), original);

    const char w = poke(root_ / "worker", 299999, 'x');
    EXPECT_NE(key(), original) << "one byte of the worker program";
    poke(root_ / "worker", 299999, w);

    fs::rename(glsl, root_ / "reference/mip/mip2.glsl");
    EXPECT_NE(key(), original) << "a file renamed";
    fs::rename(root_ / "reference/mip/mip2.glsl", glsl);

    std::ofstream(root_ / "reference/mip/extra.glsl") << "";
    EXPECT_NE(key(), original) << "an empty file added";
    fs::remove(root_ / "reference/mip/extra.glsl");
    EXPECT_EQ(key(), original);
}

}  // namespace
}  // namespace voxlab::testing
