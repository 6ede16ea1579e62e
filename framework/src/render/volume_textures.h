// voxlab internals: the volume on the GPU, as one 3D texture or as bricks
// (voxlab/volume_bricks.h). The bricks' textures are a pool: when their
// layout keeps them all resident each is uploaded once; otherwise the pool
// holds layout.resident of them, and a brick not in it is uploaded into the
// slot used longest ago, straight from the volume's memory (no copy of the
// brick is made on the CPU).
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
    VolumeTextures() = default;
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

    // The texture holding `brick`, uploaded first when it is not resident.
    unsigned texture(int brick);

    std::size_t uploads() const { return uploads_; }          // bricks uploaded since set()
    std::size_t bytesUploaded() const { return bytes_; }

private:
    const Volume* volume_ = nullptr;
    unsigned long generation_ = 0;
    BrickLayout layout_;
    glm::vec2 scaleOffset_{1.0f, 0.0f};
    std::vector<GlTexture> pool_;
    std::vector<int> holder_;           // pool slot -> brick, -1 when empty
    std::vector<long> lastUse_;         // pool slot -> when it was last used
    std::vector<int> slotOf_;           // brick -> pool slot, -1 when not resident
    long clock_ = 0;
    std::size_t uploads_ = 0, bytes_ = 0;

    void release();
};

}  // namespace voxlab
