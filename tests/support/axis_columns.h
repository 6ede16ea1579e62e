// Test support: what each pixel of an axis-aligned orthographic render sees,
// computed on the CPU from the README's conventions (not from camera.cpp or
// any shader): the column of voxels its ray passes, front to back.
//
// axisViewScene() sets up the render these columns describe: orthographic,
// nearest interpolation, step 1 (so along the ray, sample m sits exactly at
// the centre of the m-th voxel of the column), and one pixel per finer
// in-plane spacing (so pixel centres sit on voxel centres when the plane is
// isotropic and never on a voxel boundary otherwise).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "axis_views.h"
#include "voxlab/scene.h"
#include "voxlab/volume.h"

namespace voxlab::testing {

// The voxel indices on `axis` that a world coordinate may map to: none
// outside the box, two within 1e-4 voxel of an inner boundary (nearest may
// then pick either neighbour).
inline std::vector<int> voxelCandidates(const Volume& v, int axis, double world) {
    const double u = world / v.spacing()[axis];
    const int n = v.dims()[axis];
    if (u < 0.0 || u >= n) return {};
    const double r = std::round(u);
    if (std::abs(u - r) < 1e-4 && r > 0 && r < n) return {int(r) - 1, int(r)};
    return {std::min(int(std::floor(u)), n - 1)};
}

inline Scene axisViewScene(const Volume& v, const AxisView& view, const char* renderer) {
    Scene scene;
    scene.renderer = renderer;
    scene.camera.view = view.name;
    scene.camera.projection = Projection::Orthographic;
    const glm::dvec3 s = v.spacing(), ext = v.extent();
    const double pixel = std::min(s[view.rightAxis], s[view.downAxis]);
    scene.width = int(std::ceil(ext[view.rightAxis] / pixel - 1e-9));
    scene.height = int(std::ceil(ext[view.downAxis] / pixel - 1e-9));
    scene.interpolation = Interpolation::Nearest;
    scene.step = 1.0;
    return scene;
}

struct PixelColumn {
    bool inside = false;     // the ray passes through the box
    bool ambiguous = false;  // the pixel centre lies on a voxel boundary
    std::vector<double> values;  // voxel values along the ray, front to back
};

// The columns seen by the pixels of axisViewScene(v, view, ...), row by row.
// For an ambiguous pixel the first candidate voxel is used.
inline std::vector<PixelColumn> axisColumns(const Volume& v, const AxisView& view, int width, int height) {
    const glm::dvec3 ext = v.extent();
    // Uniform scale that fits the projected rectangle, centred.
    const double worldPerPixel = std::max(ext[view.rightAxis] / width, ext[view.downAxis] / height);
    std::vector<PixelColumn> out;
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            const double r = (px + 0.5 - width / 2.0) * worldPerPixel;
            const double d = (py + 0.5 - height / 2.0) * worldPerPixel;
            const std::vector<int> irs =
                voxelCandidates(v, view.rightAxis, ext[view.rightAxis] / 2 + view.rightSign * r);
            const std::vector<int> ids = voxelCandidates(v, view.downAxis, ext[view.downAxis] / 2 + view.downSign * d);
            PixelColumn c;
            if (!irs.empty() && !ids.empty()) {
                c.inside = true;
                c.ambiguous = irs.size() > 1 || ids.size() > 1;
                glm::ivec3 ijk;
                ijk[view.rightAxis] = irs[0];
                ijk[view.downAxis] = ids[0];
                const int n = v.dims()[view.fwdAxis];
                for (int m = 0; m < n; ++m) {
                    ijk[view.fwdAxis] = view.fwdSign > 0 ? m : n - 1 - m;
                    c.values.push_back(v.value(ijk.x, ijk.y, ijk.z));
                }
            }
            out.push_back(std::move(c));
        }
    return out;
}

}  // namespace voxlab::testing
