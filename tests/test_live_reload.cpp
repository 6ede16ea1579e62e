// Live reload (RenderEngine::reloadShaders): an edit that breaks a stage's
// shader keeps the last good program rendering and reports the compiler's
// message with the file and line; fixing the file brings the new program.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/gl_fixture.h"
#include "support/run_command.h"
#include "voxlab/error.h"
#include "voxlab/shader.h"
#include "voxlab/stage_registry.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

// The files watched for edits are real paths from any working folder. (The
// programs name their files relative to the project's root, for messages;
// the watcher once used those names, so a viewer started outside the root
// never saw an edit.) Also the files of the last render, which name the
// student's stage folders the checkerboard's line is made from.
TEST(LiveReload, TheWatchedFilesAreFoundFromAnyWorkingFolder) {
    auto context = createHeadlessContext();
    const fs::path before = fs::current_path();
    fs::current_path("/");
    RenderEngine engine(rendererRegistry(), std::string(VOXLAB_SOURCE_DIR) + "/assignments");
    const Volume volume = makePhantom("phantom:sphere:16");
    engine.setVolume(volume);
    Scene scene;
    scene.renderer = "mip";
    scene.width = scene.height = 16;
    engine.render(scene);
    const auto sources = engine.shaderSources();
    const auto last = engine.lastRenderSources();
    fs::current_path(before);
    ASSERT_FALSE(sources.empty());
    for (const std::string& f : sources) EXPECT_TRUE(fs::path(f).is_absolute() && fs::exists(f)) << f;
    const fs::path mip = fs::path(VOXLAB_SOURCE_DIR) / "assignments" / "mip" / "mip.glsl";
    bool found = false;
    for (const std::string& f : last) found = found || fs::equivalent(f, mip);
    EXPECT_TRUE(found) << "the last render's files miss assignments/mip/mip.glsl";
}

TEST(LiveReload, ABrokenEditKeepsTheLastGoodShaderAndSaysWhy) {
    auto context = createHeadlessContext();
    const fs::path root = fs::path(::testing::TempDir()) / ("voxlab_reload_" + std::to_string(getpid()));
    fs::remove_all(root);
    fs::create_directories(root);
    fs::copy(fs::path(VOXLAB_SOURCE_DIR) / "reference" / "mip", root / "mip", fs::copy_options::recursive);
    const fs::path mip = root / "mip" / "mip.glsl";
    const std::string good = readFile(mip);

    RenderEngine engine(rendererRegistry(), root.string());
    const Volume volume = makePhantom("phantom:sphere:16");
    engine.setVolume(volume);
    Scene scene;
    scene.renderer = "mip";
    scene.width = scene.height = 24;
    const Image before = engine.render(scene);
    EXPECT_TRUE(engine.shaderError().empty());
    const auto sources = engine.shaderSources();
    EXPECT_NE(std::find(sources.begin(), sources.end(), mip.string()), sources.end()) << "mip.glsl is not watched";

    // A syntax error: the image stays, the message names mip/mip.glsl.
    std::ofstream(mip) << good.substr(0, good.find("// BEGIN SOLUTION")) << "// BEGIN SOLUTION\n    float broken = ;\n"
                       << good.substr(good.find("// BEGIN SOLUTION") + 17);
    engine.reloadShaders();
    Image during;
    ASSERT_NO_THROW(during = engine.render(scene));
    EXPECT_EQ(during.rgba, before.rgba);
    EXPECT_NE(engine.shaderError().find("mip/mip.glsl:"), std::string::npos) << engine.shaderError();

    // A correct edit that changes the image (MIP of a constant: the ray is
    // grey 0.5 wherever it meets the volume) replaces the program.
    std::ofstream(mip) << good.substr(0, good.find("// BEGIN SOLUTION"))
                       << "// BEGIN SOLUTION\n    return 0.5 * (u_window.x + u_window.y);\n"
                       << good.substr(good.find("// BEGIN SOLUTION") + 17);
    engine.reloadShaders();
    const Image after = engine.render(scene);
    EXPECT_TRUE(engine.shaderError().empty()) << engine.shaderError();
    EXPECT_NE(after.rgba, before.rgba);
    EXPECT_NEAR(after.at(12, 12).r, 0.5f, 0.01f);

    // A program that never compiled has nothing to fall back on: it throws.
    RenderEngine fresh(rendererRegistry(), root.string());
    fresh.setVolume(volume);
    std::ofstream(mip) << "this is not GLSL\n";
    EXPECT_THROW(fresh.render(scene), ShaderError);
    fs::remove_all(root);
}

}  // namespace
}  // namespace voxlab::testing
