// Shader failures must name the file and line the student wrote, and the
// #include search path must pick the implementation root first.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "support/gl_fixture.h"
#include "voxlab/shader.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

// A temporary implementation root holding one stage file.
fs::path makeImplementation(const std::string& stage, const std::string& file, const std::string& text) {
    const fs::path root = fs::temp_directory_path() / ("voxlab_impl_" + std::to_string(::getpid()) + "_" + stage);
    fs::create_directories(root / stage);
    std::ofstream(root / stage / file) << text;
    return root;
}

TEST_F(GlTest, CompileErrorNamesTheStudentFileAndLine) {
    const fs::path root = makeImplementation("mip", "mip.glsl",
                                             "#include \"voxlab/ray.glsl\"\n"
                                             "float mip_ray(Ray ray) {\n"
                                             "    float m = 0.0;\n"
                                             "    m = undefined_thing;\n"
                                             "    return m;\n"
                                             "}\n");
    RenderEngine student(root.string());
    const Volume sphere = makePhantom("phantom:sphere:8");
    student.setVolume(sphere);
    Scene scene;
    scene.renderer = "mip";
    scene.width = scene.height = 8;
    try {
        student.render(scene);
        FAIL() << "a broken shader compiled";
    } catch (const ShaderError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find((root / "mip" / "mip.glsl").string() + ":4"), std::string::npos) << msg;
        EXPECT_NE(msg.find("undefined_thing"), std::string::npos) << msg;
    }
    fs::remove_all(root);
}

TEST_F(GlTest, MissingIncludeIsReportedWithItsIncludingLine) {
    const fs::path root = makeImplementation("mip", "mip.glsl", "\n#include \"voxlab/nope.glsl\"\n");
    const ShaderLibrary lib = ShaderLibrary::forImplementation(root.string());
    try {
        lib.preprocess("renderers/mip.frag");
        FAIL() << "a missing include was accepted";
    } catch (const ShaderError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("mip.glsl:2"), std::string::npos) << msg;
        EXPECT_NE(msg.find("voxlab/nope.glsl"), std::string::npos) << msg;
    }
    fs::remove_all(root);
}

TEST(ShaderLibrary, ImplementationRootComesFirstAndEachFileOnce) {
    const fs::path root = makeImplementation("mip", "mip.glsl", "float mip_ray(Ray r) { return 7.0; }\n");
    const ShaderLibrary lib = ShaderLibrary::forImplementation(root.string());
    const PreprocessedShader s = lib.preprocess("renderers/mip.frag");
    EXPECT_NE(s.text.find("return 7.0;"), std::string::npos);
    // ray.glsl is included by several files but appears once.
    int count = 0;
    for (const std::string& f : s.files) count += f.find("voxlab/ray.glsl") != std::string::npos;
    EXPECT_EQ(count, 1);
    EXPECT_EQ(s.text.rfind("#version 330 core", 0), 0u);
    fs::remove_all(root);
}

TEST(ShaderLibrary, LogMappingHandlesMesaAndNvidiaFormats) {
    PreprocessedShader s;
    s.files = {"renderers/mip.frag", "voxlab/ray.glsl", "mip/mip.glsl"};
    EXPECT_EQ(s.mapLog("0:200014(9): error: `x' undeclared"), "mip/mip.glsl:14:9: error: `x' undeclared");
    EXPECT_EQ(s.mapLog("0(100003) : error C1008: undefined variable"),
              "voxlab/ray.glsl:3: error C1008: undefined variable");
    EXPECT_EQ(s.mapLog("0:5(1): error: y"), "renderers/mip.frag:5:1: error: y");
}

}  // namespace
}  // namespace voxlab::testing
