// Strict GL checks (voxlab/shader.h, gl_strict.cpp): what a GPU's driver
// refuses and Mesa accepts fails on Mesa too, and KHR_debug's errors reach
// the message. The tests run with VOXLAB_GL_DEBUG=1 (tests/CMakeLists.txt),
// so every other test's draws are checked the same way.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/gl_fixture.h"
#include "voxlab/error.h"
#include "voxlab/shader.h"
#include "voxlab_gl.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

class GlStrict : public GlTest {
public:
    // On also when this binary runs outside CTest.
    static void SetUpTestSuite() {
        setenv("VOXLAB_GL_DEBUG", "1", 0);
        GlTest::SetUpTestSuite();
    }
};

// A program with a sampler2D and a sampler3D, both used.
std::unique_ptr<ShaderProgram> twoSamplerTypes() {
    const fs::path dir = fs::path(::testing::TempDir()) / ("voxlab_strict_" + std::to_string(getpid()));
    fs::create_directories(dir / "strict");
    std::ofstream(dir / "strict/two.frag") << "#version 330 core\n"
                                              "uniform sampler2D u_a;\nuniform sampler3D u_b;\nout vec4 c;\n"
                                              "void main() { c = texture(u_a, vec2(0.5)) + texture(u_b, vec3(0.5)); }\n";
    ShaderLibrary library({dir.string(), std::string(VOXLAB_SOURCE_DIR) + "/shaders"});
    return std::make_unique<ShaderProgram>(library, "voxlab/fullscreen.vert", "strict/two.frag");
}

TEST_F(GlStrict, TheTestsRunWithTheChecksOn) { EXPECT_TRUE(strictGlChecks()); }

TEST_F(GlStrict, TwoSamplerTypesOnOneUnitFailTheDraw) {
    const std::unique_ptr<ShaderProgram> program = twoSamplerTypes();
    const ShaderProgram& p = *program;
    p.use();
    p.set("u_a", 0);
    p.set("u_b", 0);  // both on unit 0, as uniforms left unset are
    GLuint vao = 0;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    try {
        checkGlDraw("drawing the strict test");
        ADD_FAILURE() << "no error for two sampler types on one unit";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("texture unit 0 is used by sampler2D u_a and by sampler3D u_b"),
                  std::string::npos) << e.what();
    }
    p.set("u_b", 1);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    EXPECT_NO_THROW(checkGlDraw("drawing the strict test"));
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glUseProgram(0);
}

// A sampler the engine never sets starts on a unit of its own type's
// (parkSamplerUniforms), not on unit 0 with the volume: found on an NVIDIA
// driver, which kept a bricked render's u_brick_state active in composite's
// back-to-front program and refused every such draw.
TEST_F(GlStrict, ASamplerLeftUnsetDoesNotShareUnitZero) {
    const std::unique_ptr<ShaderProgram> program = twoSamplerTypes();
    program->use();
    program->set("u_b", 0);  // u_a is never set
    GLuint vao = 0;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    EXPECT_NO_THROW(checkGlDraw("drawing the strict test"));
    GLint unit = -1;
    glGetUniformiv(program->id(), glGetUniformLocation(program->id(), "u_a"), &unit);
    EXPECT_GE(unit, 16);
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glUseProgram(0);
}

// A program deleted while it was current (the last of an engine that was
// destroyed) is not made current again when the next program is linked:
// parkSamplerUniforms restored it by name, and the next engine's first draw
// failed with GL_INVALID_VALUE (two engines, one after the other, in the
// coverage test's process).
TEST_F(GlStrict, LinkingAfterTheCurrentProgramWasDeletedLeavesNoError) {
    std::unique_ptr<ShaderProgram> first = twoSamplerTypes();
    first->use();
    first.reset();  // deleted while current
    EXPECT_NO_THROW(checkGlError("deleting the current program"));
    const std::unique_ptr<ShaderProgram> second = twoSamplerTypes();
    EXPECT_NO_THROW(checkGlError("linking the next program"));
    glUseProgram(0);
}

TEST_F(GlStrict, TheDriversOwnErrorMessagesAreKept) {
    glBindTexture(GL_TEXTURE_2D, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, 12345);  // GL_INVALID_ENUM
    try {
        checkGlError("a test of KHR_debug");
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("GL_INVALID_ENUM"), std::string::npos) << e.what();
        // Mesa's KHR_debug message names the call.
        EXPECT_NE(std::string(e.what()).find("glTexParameter"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace voxlab::testing
