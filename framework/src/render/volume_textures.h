// voxlab internals: the volume on the GPU, as one 3D texture or as bricks
// (voxlab/volume_bricks.h). The bricks' textures are a pool: when their
// layout keeps them all resident each is uploaded once; otherwise the pool
// holds layout.resident of them, and a brick not in it is uploaded into a
// slot straight from the volume's memory (no copy of the brick is made on
// the CPU). Bricks stay in the pool from frame to frame until their slot is
// needed.
//
// Which slot a missing brick takes (beginFrame() says which bricks the
// frame draws, in order): an empty one; else the brick used longest ago
// among those this frame does not draw (least recently used); else, when
// the frame draws more bricks than the pool holds, the brick this frame
// drew last, because the next frame, drawing much the same bricks in much
// the same order, needs it last (Belady's rule, with the next frame's order
// taken to be this one's); only when every resident brick is still to be
// drawn, the one drawn furthest ahead. With plain LRU a frame that draws
// n > resident bricks in the same order as the frame before uploads all n;
// this way it uploads n - resident + 1 at most.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/gl_object.h"
#include "voxlab/volume.h"
#include "voxlab/volume_bricks.h"

namespace voxlab {

class VolumeTextures {
public:
    // `passesExpensive`: a software renderer, where each brick's pass costs
    // tens of milliseconds (residentBricksAimed()).
    explicit VolumeTextures(bool passesExpensive) : passesExpensive_(passesExpensive) {}
    ~VolumeTextures();
    VolumeTextures(const VolumeTextures&) = delete;
    VolumeTextures& operator=(const VolumeTextures&) = delete;

    // Plans the layout of `volume` for this budget (bytes) and texture
    // limit; uploads now what stays resident. `volume` must outlive the
    // textures. Nothing changes when the same volume and budget come again.
    void set(const Volume& volume, unsigned long generation, std::size_t budgetBytes, int maxTextureSize);
    const BrickLayout& layout() const { return layout_; }
    glm::vec2 scaleOffset() const { return scaleOffset_; }
    bool resident(int brick) const { return slotOf_[std::size_t(brick)] >= 0; }

    // The bricks the coming frame will ask texture() for, in that order.
    void beginFrame(const std::vector<int>& order);
    // The texture holding `brick`, uploaded first when it is not resident.
    unsigned texture(int brick);

    std::size_t uploads() const { return uploads_; }  // bricks uploaded since the pool was made (all volumes)
    std::size_t bytesUploaded() const { return bytes_; }

private:
    bool passesExpensive_ = false;
    const Volume* volume_ = nullptr;
    unsigned long generation_ = 0;
    BrickLayout layout_;
    glm::vec2 scaleOffset_{1.0f, 0.0f};
    std::vector<GlTexture> pool_;
    std::vector<int> holder_;    // pool slot -> brick, -1 when empty
    std::vector<long> lastUse_;  // pool slot -> when it was last used
    std::vector<int> slotOf_;    // brick -> pool slot, -1 when not resident
    std::vector<int> ahead_;     // brick -> its place in the rest of this frame's order, -1 when not ahead
    long clock_ = 0, frameStart_ = 0;
    std::size_t uploads_ = 0, bytes_ = 0;

    void release();
    int slotToFill() const;
};

}  // namespace voxlab
