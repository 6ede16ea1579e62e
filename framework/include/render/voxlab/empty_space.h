// voxlab: empty-space skipping (the CPU side).
//
// Most of a CT or MRI box is air that the transfer function hides, yet a
// plain ray caster samples it as carefully as the object. Empty-space
// skipping cuts the volume into bricks (kBrickSize voxels a side) and keeps,
// for each brick, the smallest and largest value that any sample inside it
// can read. When the transfer function (or the isovalue, or the threshold)
// changes, each brick is marked visible or empty from that range alone: a
// brick whose whole range maps to zero opacity can contribute nothing, so a
// ray may leap from where it enters the brick to where it leaves it. For
// MIP the range itself is the test: a brick whose largest value cannot
// raise the ray's running maximum is passed over.
//
// What "can read" means. A trilinear sample at voxel coordinate u reads the
// voxels floor(u - 1/2) and floor(u - 1/2) + 1 on each axis, so a sample in
// brick b (u in [bB, (b+1)B)) reads voxels bB - 1 .. (b+1)B: the range
// covers the brick and an apron of one voxel around it, clamped to the grid
// (nearest and the GPU's filtering read no further). That is all a value
// test needs, shading included: a sample whose value has zero opacity adds
// nothing, whatever its gradient. Only the 2D transfer function classifies
// by the gradient, which reads one voxel further: it uses the wider range
// and the gradient bound below (computeGradientBounds).
//
// The GLSL side (shaders/voxlab/empty_space.glsl) walks rays brick by brick
// with these flags; the render engine rebuilds the ranges once per volume
// and the flags whenever the classification changes (RenderEngine::draw).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/gradients.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"

namespace voxlab {

class Volume;

// Voxels along each edge of a brick. Smaller bricks fit the object more
// tightly; larger ones let rays cross empty space in fewer leaps. See
// docs/performance.md for the measurements behind 8.
constexpr int kBrickSize = 8;

// Voxels around a brick whose values its samples can read.
constexpr int kBrickApron = 1;

struct BrickGrid {
    int brickSize = kBrickSize;
    glm::ivec3 count{0};          // bricks along each axis (the last may be partial)
    std::vector<glm::vec2> range;  // per brick, x fastest: (smallest, largest) value, data units

    // For the 2D transfer function, per brick (empty until
    // computeGradientBounds()): the value range over the brick and two
    // voxels around it (everything a gradient estimate there reads), and a
    // bound on the gradient magnitude, sqrt(Lx^2 + Ly^2 + Lz^2) with L_a the
    // largest difference of two neighbouring voxels along axis a in that
    // region. Along a line parallel to axis a the trilinear field is
    // piecewise linear with slopes that are blends of those differences, so
    // every difference quotient the estimators take (central, 26-neighbour,
    // precomputed, one-sided at the faces) is at most L_a per voxel, and at
    // most L_a per smallest spacing.
    //
    // Knowing the estimator gives a far tighter bound (boundsFor set): the
    // central difference the gradient stage takes at voxel coordinate u,
    // (f(u + e_a) - f(u - e_a)) / 2 of the trilinear field f, is the
    // trilinear interpolation, with u's own weights, of the voxels' central
    // differences D_a(i) = (V(i + e_a) - V(i - e_a)) / 2, so it is at most
    // the largest |D_a| of the voxels u reads. (Within a voxel and a half
    // of the volume's faces the stage clamps its two positions to the
    // outer voxels' centres and its quotient is a blend of the one-voxel
    // differences there: those voxels take the largest of them too.) The
    // 26-neighbour estimator is a weighted mean of such differences at
    // positions one voxel aside, so it reads one voxel further. With
    // bounds for an estimator, wideRange is the brick's range (its value
    // samples read no further) and the bound is over the voxels the
    // estimator reads; a GPU's fixed-point filtering weights add at most
    // 1/512 of the values' spread, and 1/256 is added for it.
    std::vector<glm::vec2> wideRange;
    std::vector<float> gradientBound;
    std::optional<GradientEstimator> boundsFor;  // the estimator the bounds hold for; none: any

    // Builds the grid of a volume: one pass over its voxels per brick row.
    static BrickGrid build(const Volume& volume, int brickSize = kBrickSize);
    // Fills wideRange and gradientBound, for one estimator or (none) for
    // any (about three reads per voxel; the tight bounds about fifteen).
    void computeGradientBounds(const Volume& volume, std::optional<GradientEstimator> estimator = std::nullopt);

    std::size_t brickCount() const { return range.size(); }
    std::size_t index(glm::ivec3 brick) const {
        return (std::size_t(brick.z) * std::size_t(count.y) + std::size_t(brick.y)) * std::size_t(count.x) +
               std::size_t(brick.x);
    }
    // The brick that holds continuous voxel coordinate u (clamped to the grid).
    glm::ivec3 brickAt(glm::dvec3 voxelCoordinate) const;
};

// Which bricks a renderer may skip: its rule, chosen by
// Renderer::emptySpaceRule() from its parameters.
struct EmptySpaceRule {
    enum class Kind {
        None,                // every brick may contribute (MIP, the mean, ...)
        TransferFunction,    // visible where the 1D transfer function's opacity can be > 0
        TransferFunction2D,  // the same for the 2D transfer function
        AtLeast,             // visible where a value >= threshold can occur (isosurface, first hit)
    };
    EmptySpaceRule(Kind k = Kind::None, double t = 0.0) : kind(k), threshold(t) {}
    Kind kind = Kind::None;
    double threshold = 0.0;  // AtLeast: data units
    // TransferFunction2D: the on-the-fly gradient estimator its samples
    // use, for the tight bounds; none (precomputed gradients): the bound
    // that holds for any.
    std::optional<GradientEstimator> gradients;
    // TransferFunction2D with nearest sampling: the stage's quotients near
    // the volume's faces, over a clamped distance between half a voxel and
    // one, reach twice the one-voxel difference; the bounds are doubled.
    double gradientBoundScale = 1.0;
};

// The bricks of the grid a rule skips with: kBrickSize voxels a side, but
// for the 2D transfer function as small as 2 while the grid keeps at most
// kFineGridBricks bricks. Its triangles and boxes over (value, gradient)
// show a thin shell around each boundary rather than the bulk of a
// material, which coarse bricks fit badly (docs/performance.md).
inline constexpr std::size_t kFineGridBricks = std::size_t(1) << 21;
int skippingBrickSize(const EmptySpaceRule& rule, glm::ivec3 dims);

// One byte per brick, 1 where the brick may contribute.
//
// TransferFunction: the table is read by linear interpolation between
// entries (classify.glsl), so values in [lo, hi] give weight to the entries
// from floor(x(lo)) to ceil(x(hi)); the brick is visible when any of those
// has opacity > 0.
std::vector<std::uint8_t> visibleBricks(const BrickGrid& grid, const TransferFunctionTable& table);

// TransferFunction2D: with the brick's wideRange and gradientBound (the
// grid must have them: computeGradientBounds(), else voxlab::Error), a box
// widget needs its value and gradient intervals to meet the range and
// [0, gradient bound]; Levoy's triangle (value v0, radius r) is non-zero
// where |v - v0| <= r |g|, so it needs v0 within r times the gradient bound
// of the range. The bounds must hold for the estimator the samples use.
std::vector<std::uint8_t> visibleBricks(const BrickGrid& grid, const std::vector<Tf2dWidget>& widgets,
                                        double boundScale = 1.0);

// AtLeast: visible where the brick's largest value reaches the threshold.
std::vector<std::uint8_t> bricksReaching(const BrickGrid& grid, double threshold);

// All ones: nothing may be skipped.
std::vector<std::uint8_t> allBricksVisible(const BrickGrid& grid);

}  // namespace voxlab
