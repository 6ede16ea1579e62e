// voxlab viewer: grey textures (see grey_texture.h).
#include "grey_texture.h"

#include <vector>

#include "voxlab_gl.h"

namespace voxlab::viewer {

void uploadGreyTexture(int width, int height, const std::uint8_t* bytes, GreyAs as) {
#ifdef __EMSCRIPTEN__
    std::vector<std::uint8_t> rgba(std::size_t(width) * height * 4);
    for (std::size_t i = 0; i < std::size_t(width) * height; ++i) {
        const std::uint8_t v = bytes[i];
        rgba[i * 4 + 0] = rgba[i * 4 + 1] = rgba[i * 4 + 2] = as == GreyAs::Opaque ? v : 255;
        rgba[i * 4 + 3] = as == GreyAs::Opaque ? 255 : v;
    }
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
#else
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, width, height, 0, GL_RED, GL_UNSIGNED_BYTE, bytes);
    const GLint opaque[4] = {GL_RED, GL_RED, GL_RED, GL_ONE};
    const GLint coverage[4] = {GL_ONE, GL_ONE, GL_ONE, GL_RED};
    glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, as == GreyAs::Opaque ? opaque : coverage);
#endif
}

}  // namespace voxlab::viewer
