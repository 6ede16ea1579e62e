// GL object names with an owner (voxlab/gl_object.h): each kind is made and
// deleted with its owner, moved without a second delete, and no framework
// file outside gl_object.cpp makes or deletes one by hand. The oracle is
// the GL itself: glIs* says whether a name is still an object.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "voxlab/gl_object.h"
#include "voxlab_gl.h"

#include "support/gl_fixture.h"

namespace voxlab::testing {
namespace {

class GlObjects : public GlTest {};

// A texture is an object once bound (glIsTexture is false before).
bool isTexture(unsigned name) {
    return glIsTexture(name) == GL_TRUE;
}

TEST_F(GlObjects, ATextureGoesWithItsOwner) {
    unsigned name = 0;
    {
        GlTexture texture = GlTexture::make();
        name = texture;
        ASSERT_NE(name, 0u);
        glBindTexture(GL_TEXTURE_2D, texture);
        glBindTexture(GL_TEXTURE_2D, 0);
        EXPECT_TRUE(isTexture(name));
    }
    EXPECT_FALSE(isTexture(name)) << "the texture outlived its owner";
}

TEST_F(GlObjects, AMovedObjectIsDeletedOnceByItsNewOwner) {
    GlTexture first = GlTexture::make();
    const unsigned name = first;
    glBindTexture(GL_TEXTURE_2D, name);
    glBindTexture(GL_TEXTURE_2D, 0);
    GlTexture second = std::move(first);
    EXPECT_EQ(first.name(), 0u);
    EXPECT_EQ(second.name(), name);
    first.reset();  // holds nothing: deletes nothing
    EXPECT_TRUE(isTexture(name));
    GlTexture third;
    third = std::move(second);
    EXPECT_TRUE(isTexture(name));
    third = GlTexture::make();  // the old object goes when replaced
    EXPECT_FALSE(isTexture(name));
}

TEST_F(GlObjects, EnsureMakesOnceAndResetDeletes) {
    GlBuffer buffer;
    EXPECT_EQ(buffer.name(), 0u);
    const unsigned name = buffer.ensure();
    EXPECT_EQ(buffer.ensure(), name);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    EXPECT_EQ(glIsBuffer(name), GL_TRUE);
    buffer.reset();
    EXPECT_EQ(glIsBuffer(name), GL_FALSE);
    EXPECT_EQ(buffer.name(), 0u);
}

TEST_F(GlObjects, AFloatTargetIsCompleteAndRemadeWithNewObjects) {
    GLint previous = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previous);
    FloatTarget target;
    EXPECT_FALSE(target.made());
    target.make(7, 5);
    ASSERT_TRUE(target.made());
    EXPECT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    const unsigned color = target.color, depth = target.depth, framebuffer = target.framebuffer;
    GLint width = 0;
    glBindTexture(GL_TEXTURE_2D, color);
    glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
    EXPECT_EQ(width, 7);
    target.make(9, 3);
    EXPECT_FALSE(isTexture(color));
    EXPECT_EQ(glIsRenderbuffer(depth), GL_FALSE);
    EXPECT_EQ(glIsFramebuffer(framebuffer), GL_FALSE);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previous));
    glBindTexture(GL_TEXTURE_2D, 0);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// The rule, read from the sources: glGen* and glDelete* of these kinds are
// called in gl_object.cpp only (shader.cpp's shaders and programs belong to
// ShaderProgram).
TEST(GlObjectOwners, NoFrameworkFileMakesOrDeletesAGlObjectByHand) {
    const std::filesystem::path framework = std::filesystem::path(VOXLAB_SOURCE_DIR) / "framework";
    const std::regex raw(R"(\bgl(Gen|Delete)(Textures|Framebuffers|Renderbuffers|Buffers|VertexArrays|Queries)\b)");
    std::vector<std::string> found;
    int scanned = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(framework)) {
        const std::string ext = entry.path().extension().string();
        if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
        const std::string name = entry.path().filename().string();
        if (name == "gl_object.cpp" || name.rfind("voxlab_gl", 0) == 0) continue;  // the owner, the generated loader
        ++scanned;
        std::ifstream in(entry.path());
        int number = 0;
        for (std::string line; std::getline(in, line);) {
            ++number;
            const std::string code = line.substr(0, line.find("//"));  // comments may name them
            if (std::regex_search(code, raw))
                found.push_back(entry.path().lexically_relative(framework).string() + ":" + std::to_string(number));
        }
    }
    EXPECT_GT(scanned, 100);
    EXPECT_TRUE(found.empty()) << "raw GL names without an owner at: " << ::testing::PrintToString(found);
}

TEST(GlObjectOwners, TheScanFindsAPlantedCall) {
    const std::regex raw(R"(\bgl(Gen|Delete)(Textures|Framebuffers|Renderbuffers|Buffers|VertexArrays|Queries)\b)");
    EXPECT_TRUE(std::regex_search(std::string("    glGenTextures(1, &t);"), raw));
    EXPECT_TRUE(std::regex_search(std::string("if (x) glDeleteFramebuffers(1, &f);"), raw));
    EXPECT_FALSE(std::regex_search(std::string("GlTexture::make();"), raw));
}

}  // namespace
}  // namespace voxlab::testing
