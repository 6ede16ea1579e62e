// Shader failures must name the file and line the student wrote, and the
// #include search path must pick the implementation root first.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <type_traits>
#include <utility>

#include "support/gl_fixture.h"
#include "voxlab/shader.h"
#include "voxlab/scene.h"
#include "voxlab/render_engine.h"
#include "voxlab/phantoms.h"
#include "voxlab/renderer.h"

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

// RenderEngine keeps the address of the volume it is given, so handing it a
// temporary must not compile (it did, here, and left a dangling pointer).
// Detected in an unevaluated context: a deleted overload is a substitution
// failure, so CanSetVolume<T> says whether setVolume(T) would compile.
template <class T, class = void>
struct CanSetVolume : std::false_type {};
template <class T>
struct CanSetVolume<T, std::void_t<decltype(std::declval<RenderEngine&>().setVolume(std::declval<T>()))>>
    : std::true_type {};
static_assert(CanSetVolume<Volume&>::value && CanSetVolume<const Volume&>::value,
              "setVolume takes a volume that outlives the call");
static_assert(!CanSetVolume<Volume>::value && !CanSetVolume<const Volume>::value && !CanSetVolume<Volume&&>::value,
              "setVolume must refuse temporaries: the engine keeps their address");

// Renders an 8x8 frame of `renderer` with the implementation ROOT; the
// compile error it gives ("" if the shader compiled).
std::string compileErrorOf(const fs::path& root, const std::string& renderer) {
    // Declared before the engine, which keeps its address: it must outlive it.
    const Volume volume = makePhantom("phantom:sphere:8");
    RenderEngine student(root.string());
    student.setVolume(volume);
    Scene scene;
    scene.renderer = renderer;
    scene.width = scene.height = 8;
    try {
        student.render(scene);
    } catch (const ShaderError& e) {
        return e.what();
    }
    return "";
}

TEST_F(GlTest, CompileErrorNamesTheStudentFileAndLine) {
    const fs::path root = makeImplementation("mip", "mip.glsl",
                                             "#include \"voxlab/ray.glsl\"\n"
                                             "float mip_ray(Ray ray) {\n"
                                             "    float m = 0.0;\n"
                                             "    m = undefined_thing;\n"
                                             "    return m;\n"
                                             "}\n");
    const std::string msg = compileErrorOf(root, "mip");
    ASSERT_FALSE(msg.empty()) << "a broken shader compiled";
    EXPECT_NE(msg.find((root / "mip" / "mip.glsl").string() + ":4"), std::string::npos) << msg;
    EXPECT_NE(msg.find("undefined_thing"), std::string::npos) << msg;
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

// A ray-value stage has no entry shader file: RayValueRenderer makes it
// from shaders/renderers/ray_value.frag.in, and the engine adds it to its
// library. The generated shader includes the implementation's stage file
// (so a student's mistake is named in their file), and a name added as
// generated resolves before the search path.
TEST_F(GlTest, ARayValueStagesEntryShaderIsMadeFromTheTemplate) {
    const fs::path root = makeImplementation("minip", "minip.glsl",
                                             "float minip_ray(Ray ray) {\n    return undefined_thing;\n}\n");
    const std::string msg = compileErrorOf(root, "minip");
    ASSERT_FALSE(msg.empty()) << "the generated entry shader did not include the broken minip.glsl";
    EXPECT_NE(msg.find("minip.glsl:2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("undefined_thing"), std::string::npos) << msg;
    const auto generated = rendererRegistry().get("minip").generatedShaders();
    ASSERT_EQ(generated.size(), 1u);
    const std::string& text = generated.at("renderers/minip.frag");
    EXPECT_EQ(text.rfind("#version 330 core", 0), 0u);
    EXPECT_NE(text.find("#include \"minip/minip.glsl\""), std::string::npos) << text;
    // MinIP's value is the smallest over runs between bricks (voxlab/runs.glsl).
    EXPECT_NE(text.find("#define RUN_SMALLEST minip_ray"), std::string::npos) << text;
    EXPECT_NE(text.find("#define RAY_VALUE smallest_over_runs"), std::string::npos) << text;
    EXPECT_EQ(text.find("STAGE_NAME"), std::string::npos) << text;
    EXPECT_EQ(text.find("RUN_DEFINES"), std::string::npos) << text;
    // The average needs the whole ray in one call.
    const std::string average = rendererRegistry().get("average").generatedShaders().at("renderers/average.frag");
    EXPECT_NE(average.find("#define RAY_VALUE average_ray"), std::string::npos) << average;
    EXPECT_EQ(average.find("RUN_"), std::string::npos) << average;
    ShaderLibrary lib = ShaderLibrary::forImplementation(root.string());
    lib.addGenerated("renderers/minip.frag", text);
    EXPECT_EQ(lib.resolve("renderers/minip.frag"), "generated:renderers/minip.frag");
    const PreprocessedShader s = lib.preprocess("renderers/minip.frag");
    EXPECT_NE(s.text.find("return undefined_thing;"), std::string::npos);
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
