// Shader failures must name the file and line the student wrote, and the
// #include search path must pick the implementation root first.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <type_traits>
#include <utility>

#include "support/error_of.h"
#include "support/gl_fixture.h"
#include "voxlab_gl.h"
#include "voxlab/gl_context.h"
#include "voxlab/project_root.h"
#include "voxlab/shader.h"
#include "voxlab/scene.h"
#include "voxlab/render_engine.h"
#include "voxlab/phantoms.h"
#include "voxlab/renderer.h"
#include "voxlab/stage_registry.h"

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
    RenderEngine student(rendererRegistry(), root.string());
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
        lib.preprocess("stages/mip/mip.frag");
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
    const PreprocessedShader s = lib.preprocess("stages/mip/mip.frag");
    EXPECT_NE(s.text.find("return 7.0;"), std::string::npos);
    // ray.glsl is included by several files but appears once.
    int count = 0;
    for (const std::string& f : s.files) count += f.find("voxlab/ray.glsl") != std::string::npos;
    EXPECT_EQ(count, 1);
    EXPECT_EQ(s.text.rfind("#version 330 core", 0), 0u);
    fs::remove_all(root);
}

// A name "stages/STAGE/FILE" is the framework's stage folder's alone: an
// implementation's own stages/ folder is never read, and of the folder only
// shader files are (it also holds the stage's C++ and oracle tests, which
// an #include would print into a compile log).
TEST(ShaderLibrary, StageFolderNamesReachOnlyTheFrameworksShaders) {
    const fs::path root = makeImplementation("mip", "mip.glsl", "float mip_ray(Ray r) { return 7.0; }\n");
    fs::create_directories(root / "stages" / "mip");
    std::ofstream(root / "stages" / "mip" / "mip.frag") << "#version 330 core\nPLANTED\n";
    const ShaderLibrary lib = ShaderLibrary::forImplementation(root.string());
    EXPECT_EQ(lib.resolve("stages/mip/mip.frag"), stagesRoot() + "/mip/mip.frag");
    EXPECT_EQ(lib.preprocess("stages/mip/mip.frag").text.find("PLANTED"), std::string::npos);
    for (const char* name : {"stages/iso/test_iso.cpp", "stages/mip/renderer.cpp", "stages/stages.cmake"})
        EXPECT_NE(errorOf([&] { lib.resolve(name); }).find("not a .glsl, .frag or .vert file"), std::string::npos)
            << name;
    EXPECT_NE(errorOf([&] { lib.resolve("stages/../shaders/voxlab/ray.glsl"); }).find("without '..'"),
              std::string::npos);
    fs::remove_all(root);
}

// "stages/*/FILE" reads every stage folder's FILE (the oracle: the folders
// themselves), and nothing when no folder has one. That is how ray.glsl gets the cutting plane's half-space tests
// without naming the stage: the student's cutting_plane.glsl is in every
// ray shader, here mip's.
TEST(ShaderLibrary, AStageSegmentIsReadFromEveryStageFolderThatHasOne) {
    std::vector<std::string> expected;
    for (const auto& entry : fs::directory_iterator(stagesRoot()))
        if (fs::is_regular_file(entry.path() / "ray_segment.glsl")) expected.push_back((entry.path() / "ray_segment.glsl").string());
    std::sort(expected.begin(), expected.end());
    ASSERT_FALSE(expected.empty());
    const fs::path root = makeImplementation("cutting_plane", "cutting_plane.glsl",
                                             "bool clip_to_half_space(inout Ray r, vec3 p, vec3 n) { return true; }\n"
                                             "bool in_half_space(vec3 q, vec3 p, vec3 n) { return true; } // PLANTED\n");
    const ShaderLibrary lib = ShaderLibrary::forImplementation(root.string());
    std::vector<std::string> found = lib.resolveAll("stages/*/ray_segment.glsl");
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected);
    EXPECT_TRUE(lib.resolveAll("stages/*/no_such_segment.glsl").empty());
    EXPECT_EQ(lib.resolveAll("voxlab/ray.glsl"), std::vector<std::string>{lib.resolve("voxlab/ray.glsl")});
    EXPECT_NE(errorOf([&] { lib.resolveAll("stages/*/../../shaders/voxlab/ray.glsl"); }).find("without '..'"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { lib.resolveAll("stages/*/renderer.cpp"); }).find("not a .glsl, .frag or .vert file"),
              std::string::npos);
    EXPECT_NE(lib.preprocess("stages/mip/mip.frag").text.find("PLANTED"), std::string::npos);
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
    const std::string& text = generated.at("stages/minip/minip.frag");
    EXPECT_EQ(text.rfind("#version 330 core", 0), 0u);
    EXPECT_NE(text.find("#include \"minip/minip.glsl\""), std::string::npos) << text;
    // MinIP's value is the smallest over runs between bricks (voxlab/runs.glsl).
    EXPECT_NE(text.find("#define RUN_SMALLEST minip_ray"), std::string::npos) << text;
    EXPECT_NE(text.find("#define RAY_VALUE smallest_over_runs"), std::string::npos) << text;
    EXPECT_EQ(text.find("STAGE_NAME"), std::string::npos) << text;
    EXPECT_EQ(text.find("RUN_DEFINES"), std::string::npos) << text;
    // The average needs the whole ray in one call.
    const std::string average = rendererRegistry().get("average").generatedShaders().at("stages/average/average.frag");
    EXPECT_NE(average.find("#define RAY_VALUE average_ray"), std::string::npos) << average;
    EXPECT_EQ(average.find("RUN_"), std::string::npos) << average;
    ShaderLibrary lib = ShaderLibrary::forImplementation(root.string());
    lib.addGenerated("stages/minip/minip.frag", text);
    EXPECT_EQ(lib.resolve("stages/minip/minip.frag"), "generated:stages/minip/minip.frag");
    const PreprocessedShader s = lib.preprocess("stages/minip/minip.frag");
    EXPECT_NE(s.text.find("return undefined_thing;"), std::string::npos);
    fs::remove_all(root);
}

// With setCompileOnce, on llvmpipe a fragment shader's main() is renamed and
// called from a main() that may discard (so that the driver compiles it once,
// see shader.cpp).
// The shader must mean what it says: an early return from main, a function
// whose name starts with "main", and every pixel written exactly.
TEST_F(GlTest, AnEntryShaderMeansWhatItSaysWhateverTheDriver) {
    const int n = 8;
    GLuint texture = 0, fbo = 0, vao = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, n, n, 0, GL_RGBA, GL_FLOAT, nullptr);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    ShaderLibrary lib({});
    lib.setCompileOnce(true);
    lib.addGenerated("t.vert", "#version 330 core\nvoid main() {\n"
                               "    vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
                               "    gl_Position = vec4(p, 0.0, 1.0);\n}\n");
    lib.addGenerated("t.frag", "#version 330 core\nout vec4 colour;\nuniform float u_half;\n"
                               "vec4 main_colour() { return vec4(0.25, 0.5, 0.75, 0.125); }\n"
                               "void main(void) {\n    colour = main_colour();\n"
                               "    if (gl_FragCoord.x < u_half) return;\n    colour.r = 1.0;\n}\n");
    {
        ShaderProgram prog(lib, "t.vert", "t.frag");
        // The wrapper's uniform is live exactly where the wrapper was applied.
        const bool llvmpipe = currentGlRenderer().find("llvmpipe") != std::string::npos;
        EXPECT_EQ(prog.location("voxlab_never_set") >= 0, llvmpipe) << currentGlRenderer();
        ShaderLibrary asWritten = lib;
        asWritten.setCompileOnce(false);
        EXPECT_LT(ShaderProgram(asWritten, "t.vert", "t.frag").location("voxlab_never_set"), 0);
        prog.use();
        prog.set("u_half", float(n) / 2.0f);
        glViewport(0, 0, n, n);
        glDisable(GL_BLEND);
        glGenVertexArrays(1, &vao);
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        std::vector<float> got(std::size_t(n) * n * 4, -1.0f);
        glReadPixels(0, 0, n, n, GL_RGBA, GL_FLOAT, got.data());
        checkGlError("the test's draw");
        for (std::size_t i = 0; i < got.size(); ++i) {
            const int x = int(i / 4) % n;
            const float want[4] = {x < n / 2 ? 0.25f : 1.0f, 0.5f, 0.75f, 0.125f};
            ASSERT_EQ(got[i], want[i % 4]) << "pixel " << i / 4 << ", channel " << i % 4;
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &texture);
}

TEST(ShaderLibrary, LogMappingHandlesMesaAndNvidiaFormats) {
    PreprocessedShader s;
    s.files = {"stages/mip/mip.frag", "voxlab/ray.glsl", "mip/mip.glsl"};
    EXPECT_EQ(s.mapLog("0:200014(9): error: `x' undeclared"), "mip/mip.glsl:14:9: error: `x' undeclared");
    EXPECT_EQ(s.mapLog("0(100003) : error C1008: undefined variable"),
              "voxlab/ray.glsl:3: error C1008: undefined variable");
    EXPECT_EQ(s.mapLog("0:5(1): error: y"), "stages/mip/mip.frag:5:1: error: y");
}

// The directives and the compiler's log are read by hand-written scans
// (no std::regex, which recursed per character: a line of 200 000 spaces
// overflowed the stack). They mean what the regular expressions meant.
TEST(ShaderLibrary, DirectivesAreReadByScansThatMeanWhatTheExpressionsMeant) {
    const fs::path root = fs::temp_directory_path() / ("voxlab_scan_" + std::to_string(::getpid()));
    fs::create_directories(root);
    std::ofstream(root / "a.glsl") << "float from_a;\n";
    std::ofstream(root / "entry.frag") << "#version 330 core // the version\r\n"
                                       << "  #  include   \"a.glsl\"   // included\n"
                                       << "#include \"b.glsl\" // a CR ends this comment\r\n"
                                       << "#include \"\"\n"
                                       << "uniform int  N ;  // baked\n"
                                       << "uniform bool\tB;\n"
                                       << "uniform integer M;\n"
                                       << "uniform int K; int k2;\n"
                                       << std::string(200000, ' ') << "\n"
                                       << "out vec4 c;\nvoid main ( void ) { c = vec4(N); }\n";
    const ShaderLibrary lib({root.string()});
    const PreprocessedShader s = lib.preprocess("entry.frag", {{"N", 7}, {"B", 1}, {"M", 2}, {"K", 3}});
    EXPECT_NE(s.text.find("float from_a;"), std::string::npos);
    EXPECT_NE(s.text.find("#include \"b.glsl\" // a CR ends this comment\r\n"), std::string::npos);
    EXPECT_NE(s.text.find("#include \"\"\n"), std::string::npos);
    EXPECT_NE(s.text.find("const int N = 7;"), std::string::npos);
    EXPECT_NE(s.text.find("const int B = 1;"), std::string::npos);
    EXPECT_NE(s.text.find("uniform integer M;"), std::string::npos);
    EXPECT_NE(s.text.find("uniform int K; int k2;"), std::string::npos);
    fs::remove_all(root);

    for (const char* ok : {"#version 330", "#version 330 core", "  # version  330\tcore  ", "#version 330\r",
                           "#version 330 core // c\r", "#version 330 core\r"})
        EXPECT_NO_THROW(versionPreamble(ok, GlslDialect::Core330, "x")) << ok;
    for (const char* bad : {"#version 3300", "#version 330 corex", "#version 330core", "#version 330 // c\rx",
                            "#version 450 core", "version 330"})
        EXPECT_THROW(versionPreamble(bad, GlslDialect::Core330, "x"), ShaderError) << bad;
    EXPECT_THROW(versionPreamble(std::string(200000, ' '), GlslDialect::Core330, "x"), ShaderError);
}

TEST(ShaderLibrary, LogMappingHandlesAngleAndLeavesOtherLinesAlone) {
    PreprocessedShader s;
    s.files = {"stages/mip/mip.frag", "voxlab/ray.glsl", "mip/mip.glsl"};
    EXPECT_EQ(s.mapLog("ERROR: 0:100002: 'x' : undeclared identifier"),
              "voxlab/ray.glsl:2: error: 'x' : undeclared identifier");
    EXPECT_EQ(s.mapLog("WARNING:0:5:   unused"), "stages/mip/mip.frag:5: warning: unused");
    EXPECT_EQ(s.mapLog("0:300001(2): error: y"), "<source 3>:1:2: error: y");
    EXPECT_EQ(s.mapLog("0:5(1): error: y\r"), "0:5(1): error: y\r");  // as std::regex's `.*$` had it
    EXPECT_EQ(s.mapLog("0:5(1):   \r"), "stages/mip/mip.frag:5:1: ");
    const std::string huge = "0:" + std::string(25, '9') + "(1): error: z";  // std::stol threw out_of_range
    EXPECT_EQ(s.mapLog(huge), huge);
    const std::string longLine = std::string(200000, ' ') + "x";
    EXPECT_EQ(s.mapLog(longLine), longLine);
    EXPECT_EQ(s.mapLog("\n\n"), "shader compilation failed with an empty log");
}

}  // namespace
}  // namespace voxlab::testing
