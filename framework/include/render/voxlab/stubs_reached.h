#pragma once
// voxlab: the stubs a render reached, read from its image and the engine.
#include <string>
#include <vector>

namespace voxlab {

class RenderEngine;
struct Image;
struct Scene;

// Whether an image shows the stubs' magenta-and-black checkerboard.
bool showsStubPattern(const Image& image);
// The stubs a render reached, once it shows the checkerboard: the functions
// whose stub ran for some pixel (RenderEngine::stubsReached). Empty when the
// image shows no checkerboard.
std::vector<std::string> stubsReached(RenderEngine& engine, const Scene& scene, const Image& image, int maxSide = 0);

}  // namespace voxlab
