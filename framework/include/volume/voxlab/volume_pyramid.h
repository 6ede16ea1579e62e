// voxlab: coarser levels of a volume, for drawing while the view moves.
//
// Level 0 is the volume itself; level n + 1 halves level n along each axis
// whose size is above 1: voxel i of the coarser level is the mean of voxels
// 2i and 2i + 1 of the finer one (only 2i at the far end of an odd size),
// along each halved axis at once: a mean of up to 2x2x2 voxels, the octree's
// node value in the tutorial's terms. The box stays where it is: the spacing
// grows so that dims x spacing is the same at every level. With an even
// size, the coarse voxel's centre is the centre of the fine voxels it
// averages ((i + 1/2) x 2s = the mean of (2i + 1/2) s and (2i + 3/2) s); an
// odd size's last voxel sits a little off, which a level shown only while
// the view moves can afford. Integer types are rounded to the nearest value;
// the value range can only shrink.
#pragma once

#include "voxlab/volume.h"

namespace voxlab {

// The next coarser level (its name: the volume's with "@1/2").
Volume halveVolume(const Volume& volume);

// How many levels to go down so that a moving view draws at most about
// `voxels` voxels: 0 for a volume already that small.
int coarseLevelFor(glm::ivec3 dims, double voxels);

}  // namespace voxlab
