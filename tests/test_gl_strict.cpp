// Strict GL checks (voxlab/shader.h, gl_strict.cpp): what a GPU's driver
// refuses and Mesa accepts fails on Mesa too, and KHR_debug's errors reach
// the message. The tests run with VOXLAB_GL_DEBUG=1 (tests/CMakeLists.txt),
// so every other test's draws are checked the same way.
//
// Each test runs in a child process with a context of its own, which ends
// with _exit: Mesa's OSMesaDestroyContext crashed at this program's exit
// after these raw draws (not after the engine's), which says nothing of
// what is tested here.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

#include "support/in_child.h"
#include "voxlab/error.h"
#include "voxlab/gl_context.h"
#include "voxlab/shader.h"
#include "voxlab_gl.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

// Runs `body` in a child with a headless context and the strict checks on;
// returns what it returned, or the message of what it threw.
std::string inStrictContext(const std::function<std::string()>& body) {
    return messageInChild([] { return setenv("VOXLAB_GL_DEBUG", "1", 1) == 0; },
                          [&] {
                              const std::unique_ptr<GlContext> context = createHeadlessContext();
                              return body();
                          });
}

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

// Draws a full-screen triangle and returns checkGlDraw's message, or "ok".
std::string drawAndCheck() {
    GLuint vao = 0;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::string result = "ok";
    try {
        checkGlDraw("drawing the strict test");
    } catch (const Error& e) {
        result = e.what();
    }
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    return result;
}

TEST(GlStrict, TheChecksAreOnWhereWanted) {
    EXPECT_EQ(inStrictContext([] { return std::string(strictGlChecks() ? "on" : "off"); }), "on");
}

TEST(GlStrict, TwoSamplerTypesOnOneUnitFailTheDraw) {
    const std::string both = inStrictContext([] {
        const std::unique_ptr<ShaderProgram> p = twoSamplerTypes();
        p->use();
        p->set("u_a", 0);
        p->set("u_b", 0);  // both on unit 0, as uniforms left unset were
        return drawAndCheck();
    });
    EXPECT_NE(both.find("texture unit 0 is used by sampler2D u_a and by sampler3D u_b"), std::string::npos) << both;
    const std::string apart = inStrictContext([] {
        const std::unique_ptr<ShaderProgram> p = twoSamplerTypes();
        p->use();
        p->set("u_a", 0);
        p->set("u_b", 1);
        return drawAndCheck();
    });
    EXPECT_EQ(apart, "ok");
}

// A sampler the engine never sets starts on a unit of its own type's
// (parkSamplerUniforms), not on unit 0 with the volume: found on an NVIDIA
// driver, which kept a bricked render's u_brick_state active in composite's
// back-to-front program and refused every such draw.
TEST(GlStrict, ASamplerLeftUnsetDoesNotShareUnitZero) {
    const std::string got = inStrictContext([] {
        const std::unique_ptr<ShaderProgram> p = twoSamplerTypes();
        p->use();
        p->set("u_b", 0);  // u_a is never set
        GLint unit = -1;
        glGetUniformiv(p->id(), glGetUniformLocation(p->id(), "u_a"), &unit);
        return drawAndCheck() + " unit " + std::to_string(unit);
    });
    EXPECT_EQ(got.rfind("ok unit ", 0), 0u) << got;
    EXPECT_GE(std::atoi(got.c_str() + 8), 16) << got;
}

TEST(GlStrict, TheDriversOwnErrorMessagesAreKept) {
    const std::string got = inStrictContext([] {
        glBindTexture(GL_TEXTURE_2D, 0);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, 12345);  // GL_INVALID_ENUM
        checkGlError("a test of KHR_debug");
        return std::string("no error");
    });
    EXPECT_NE(got.find("GL_INVALID_ENUM"), std::string::npos) << got;
    EXPECT_NE(got.find("glTexParameter"), std::string::npos) << got;  // Mesa's KHR_debug message names the call
}

}  // namespace
}  // namespace voxlab::testing
