// voxlab grader internals: the stage host's wire protocol (stage_host.h
// describes it), shared by the worker's side (stage_host.cpp) and the host
// program (framework/stage_host/stage_host_main.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include <glm/glm.hpp>

#include "voxlab/camera.h"
#include "voxlab/fd_io.h"

namespace voxlab::stage_host {

constexpr std::uint32_t kMaxPoints = 64;      // a plane meets a box in at most 6
constexpr std::uint32_t kMaxMessage = 4096;
constexpr std::uint32_t kMaxBatch = 1u << 14;  // calls in one batch ('c', 'x')
// The host reads calls on stdin and answers on fd 3, so that what the
// stage prints (stdout, stderr) goes to the worker's log, not into answers.
constexpr int kAnswers = 3;

// Writes `size` bytes from `data` whole (fd_io.h).
inline bool sendAll(int fd, const void* data, std::size_t size) {
    return writeAll(fd, std::string_view(static_cast<const char*>(data), size)) == 0;
}

// The doubles a call of `op` carries.
inline int argumentCount(char op) { return op == 'P' ? 10 : op == 'A' || op == 'S' ? 3 : op == 'W' ? 22 : 9; }

// A camera and a grid as the 22 doubles of a 'W' call, and back.
inline void packShearWarpCall(const Camera& cam, glm::ivec3 dims, glm::dvec3 spacing, double* a) {
    const glm::dvec3 vectors[4] = {cam.position, cam.forward, cam.right, cam.down};
    for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) a[3 * v + k] = vectors[v][k];
    a[12] = cam.pixelScale, a[13] = cam.width, a[14] = cam.height;
    a[15] = cam.projection == Projection::Orthographic ? 0.0 : 1.0;
    for (int k = 0; k < 3; ++k) a[16 + k] = dims[k], a[19 + k] = spacing[k];
}

inline Camera unpackCamera(const double* a) {
    Camera cam;
    cam.position = {a[0], a[1], a[2]}, cam.forward = {a[3], a[4], a[5]};
    cam.right = {a[6], a[7], a[8]}, cam.down = {a[9], a[10], a[11]};
    cam.pixelScale = a[12], cam.width = int(a[13]), cam.height = int(a[14]);
    cam.projection = a[15] == 0.0 ? Projection::Orthographic : Projection::Perspective;
    return cam;
}

}  // namespace voxlab::stage_host
