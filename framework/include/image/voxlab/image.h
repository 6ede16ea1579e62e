// voxlab: float RGBA images and PNG files.
//
// Renderers produce linear float RGBA (rows top to bottom). A PNG pixel is
// round(clamp(x, 0, 1) * 255), the rule stated in the README; nothing else
// (no gamma) happens on the way to the file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace voxlab {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;  // width*height*4, row 0 at the top

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * h * 4, 0.0f) {}

    glm::vec4 at(int x, int y) const {
        const float* p = &rgba[(std::size_t(y) * width + x) * 4];
        return {p[0], p[1], p[2], p[3]};
    }
    void set(int x, int y, glm::vec4 c) {
        float* p = &rgba[(std::size_t(y) * width + x) * 4];
        p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = c.a;
    }
};

// The 8-bit value a float channel becomes in a PNG.
std::uint8_t toByte(float x);

// Writes an RGB PNG (alpha dropped: colours are already over the
// background) through writeFileAtomically (atomic_file.h): a failed save
// leaves the old file. Creates no folders. Throws voxlab::Error naming the
// path.
void savePng(const Image& image, const std::string& path);

// Reads a PNG (any channel count) into an Image with values k/255.
Image loadPng(const std::string& path);

}  // namespace voxlab
