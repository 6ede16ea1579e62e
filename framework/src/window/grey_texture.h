// voxlab viewer (internal): one channel of bytes as a 2D texture that
// ImGui's shader shows as grey or as white coverage.
#pragma once

#include <cstdint>

namespace voxlab::viewer {

enum class GreyAs {
    Opaque,    // (v, v, v, 1): a slice image
    Coverage,  // (1, 1, 1, v): counts blended over what is behind
};

// Into the bound GL_TEXTURE_2D, rows packed (unpack alignment 1 is the
// caller's). Natively R8 with a texture swizzle; WebGL 2 has no swizzle, so
// there the bytes are expanded to RGBA8.
void uploadGreyTexture(int width, int height, const std::uint8_t* bytes, GreyAs as);

}  // namespace voxlab::viewer
