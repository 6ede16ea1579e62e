// voxlab: which stubs a render reached (voxlab/stubs_reached.h).
#include "voxlab/stubs_reached.h"

#include "voxlab/image.h"
#include "voxlab/render_engine.h"

namespace voxlab {

bool showsStubPattern(const Image& image) {
    // The stub's magenta (1, 0, 1), exact in a float image and in one read
    // back from 8 bits; a real rendering has it by chance in a pixel or two
    // at most, the checkerboard in 32 of every 64 pixels it covers.
    int magenta = 0;
    for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4)
        if (image.rgba[i] > 0.996f && image.rgba[i + 1] < 0.004f && image.rgba[i + 2] > 0.996f && ++magenta >= 8)
            return true;
    return false;
}

std::vector<std::string> stubsReached(RenderEngine& engine, const Scene& scene, const Image& image, int maxSide) {
    if (engine.lastRenderStubs().empty() || !showsStubPattern(image)) return {};
    return engine.stubsReached(scene, maxSide);
}

}  // namespace voxlab
