// voxlab: a volume larger than one texture, cut into bricks.
//
// A GPU holds a 3D texture of at most GL_MAX_3D_TEXTURE_SIZE voxels along
// each axis (2048 on llvmpipe), and only as many bytes as its memory. A
// volume beyond either is cut into bricks: a grid of boxes of voxels, each
// uploaded as a texture of its own with an apron, the voxels around it that
// the renderers read near its faces. The renderers then draw the bricks one
// after the other, in visibility order, each pass taking the samples that lie
// inside its brick and adding them to what the passes before it left
// (RenderEngine, shaders/voxlab/bricks.glsl). The samples stay where they
// are in the whole volume, so the image is the unbricked one.
//
// Conventions (the README's): voxel (i, j, k) is centred at (i + 1/2) spacing;
// brick b owns the world box [lo * spacing, hi * spacing) of its voxel range
// [lo, hi): a sample on a face between two bricks belongs to the brick
// behind that face (half-open along every axis; the volume's far faces
// belong to the last brick).
//
// The apron is kTextureBrickApron voxels on every side (fewer where the volume
// ends): trilinear interpolation reads one voxel beyond its cell, a central
// difference of trilinear samples one more, and the isosurface's crossing
// test looks one sample (at most one voxel, bricked scenes need a step of
// at most 1) before the brick's face: 1 + 1 + 1 = 3.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace voxlab {

inline constexpr int kTextureBrickApron = 3;

// A volume that does not fit the budget is cut into bricks small enough
// that at least this many fit it at once: a frame then keeps most of the
// bricks it draws on the GPU for the next one (render/volume_textures.h).
inline constexpr std::size_t kResidentBricksAimed = 8;

// How many bricks a plan should keep on the GPU at once: kResidentBricksAimed,
// except where passes are expensive (a software renderer: a full-screen
// pass at 512^2 costs about 30 ms on llvmpipe with 2 threads) and the volume
// is over twice the budget, so that most bricks are uploaded every frame
// anyway: then 1 (bricks as large as fit, the fewest passes). Measured on
// 1024^3 bonsai, 256 MiB, compositing at 512^2: 8 bricks a frame took 803 ms,
// 36 (8 resident, 28 uploaded) 1660 ms.
std::size_t residentBricksAimed(std::size_t volumeBytes, std::size_t budgetBytes, bool passesExpensive);

struct VolumeBrick {
    glm::ivec3 lo{0}, hi{0};                   // the voxels it owns, [lo, hi)
    glm::ivec3 textureOrigin{0}, textureSize{0};  // what its texture holds: the apron included, inside the volume
    std::size_t bytes = 0;                     // its texture's size
};

struct BrickLayout {
    glm::ivec3 count{1};   // bricks along each axis
    glm::ivec3 core{0};    // voxels each owns along each axis (the last ones fewer)
    std::vector<VolumeBrick> bricks;  // x fastest, then y, then z
    std::size_t resident = 0;         // textures kept on the GPU at once
    std::size_t budgetBytes = 0;
    bool bricked() const { return bricks.size() > 1; }
    std::size_t totalBytes() const;
};

// Plans the bricks of a volume of `dims` voxels of `bytesPerVoxel` bytes for
// a GPU whose 3D textures hold at most `maxTextureSize` voxels per axis, in
// at most `budgetBytes` of texture memory. A volume that fits both is one
// brick without an apron (the unbricked path). Otherwise the axis with the
// largest bricks is split again until each brick's texture fits both and
// either all bricks fit the budget together (all stay resident) or
// `aimedResident` of them do (bricks of at least 16 voxels a side
// permitting); then as many as fit stay resident, and the others are
// uploaded as the passes need them. Throws a one-line
// Error when the budget cannot hold a single brick of at least 16 voxels a
// side with its apron.
BrickLayout planBricks(const glm::ivec3& dims, int bytesPerVoxel, int maxTextureSize, std::size_t budgetBytes,
                       std::size_t aimedResident = kResidentBricksAimed);

// The order in which to draw the bricks so that every ray meets them front
// to back: along any ray the brick index changes monotonically on each axis,
// moving away from the eye, so the sum over the axes of the index distance
// from the eye's brick (for an orthographic view: from the side the rays
// come from) grows strictly from one brick of a ray to the next. `eye` and
// `forward` are in voxel coordinates (world / spacing).
std::vector<int> frontToBackOrder(const BrickLayout& layout, const glm::dvec3& eye, const glm::dvec3& forward,
                                  bool orthographic);

}  // namespace voxlab
