// voxlab internals shared by the render engine's files: the texture units
// the framework's GLSL libraries read, and the GPU memory budget's default.
#pragma once

#include <cstddef>

namespace voxlab {

constexpr int kVolumeUnit = 0;
constexpr int kTransferFunctionUnit = 1;
constexpr int kGradientUnit = 2;
constexpr int kLayerUnit = 3;  // and kLayerUnit + 1 (cut_compose.frag); a bricked render's state
constexpr int kBsplineUnit = 9;  // after the precomputed textures (6, 7)

// The texture memory the driver says the GPU has for the volume (see
// RenderEngine::defaultGpuMemoryBudget); needs a current context.
std::size_t driverGpuMemoryBudget();

// Whether the current context draws on the CPU (Mesa's llvmpipe or
// softpipe), where every full-screen pass costs tens of milliseconds.
bool softwareRenderer();

}  // namespace voxlab
