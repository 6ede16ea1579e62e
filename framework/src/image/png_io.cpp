// voxlab: PNG reading and writing through stb (Debian's libstb, which ships
// the implementations in libstb.a, so no STB_*_IMPLEMENTATION here).
#include <stb_image.h>
#include <stb_image_write.h>

#include <cmath>
#include <string>

#include "voxlab/atomic_file.h"
#include "voxlab/error.h"
#include "voxlab/image.h"

namespace voxlab {

std::uint8_t toByte(float x) {
    if (!(x > 0.0f)) return 0;  // also maps NaN to 0
    if (x >= 1.0f) return 255;
    return std::uint8_t(std::lround(x * 255.0f));
}

namespace {

// stb's output callback: appends each piece of the encoded PNG to a string.
void appendToString(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}

}  // namespace

// The PNG is encoded in memory and then saved by writeFileAtomically: stb's
// own file writer neither checks fwrite nor fclose (a full disk gave a
// truncated file and success) and writes over the old file as it goes.
void savePng(const Image& image, const std::string& path) {
    if (image.width <= 0 || image.height <= 0) throw Error(path + ": cannot write an empty image");
    std::vector<std::uint8_t> rgb(std::size_t(image.width) * image.height * 3);
    for (std::size_t i = 0, n = std::size_t(image.width) * image.height; i < n; ++i)
        for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = toByte(image.rgba[i * 4 + c]);
    std::string png;
    if (!stbi_write_png_to_func(appendToString, &png, image.width, image.height, 3, rgb.data(), image.width * 3) ||
        png.empty())
        throw Error(path + ": cannot encode PNG (" + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + ")");
    writeFileAtomically(path, png);
}

Image loadPng(const std::string& path) {
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 4);
    if (!data) throw Error(path + ": cannot read PNG (" + stbi_failure_reason() + ")");
    Image img(w, h);
    for (std::size_t i = 0; i < std::size_t(w) * h * 4; ++i) img.rgba[i] = data[i] / 255.0f;
    stbi_image_free(data);
    return img;
}

}  // namespace voxlab
