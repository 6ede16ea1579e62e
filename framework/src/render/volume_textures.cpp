// The volume's textures: one, or a pool of bricks (see volume_textures.h).
#include "volume_textures.h"

#include <algorithm>

#include "voxlab/scene_volumes.h"
#include "voxlab_gl.h"

namespace voxlab {

VolumeTextures::~VolumeTextures() { release(); }

void VolumeTextures::release() {
    pool_.clear();
    holder_.clear();
    lastUse_.clear();
    slotOf_.clear();
}

void VolumeTextures::set(const Volume& volume, unsigned long generation, std::size_t budgetBytes, int maxTextureSize) {
    if (volume_ == &volume && generation_ == generation && layout_.budgetBytes == budgetBytes && !pool_.empty()) return;
    release();
    layout_ = planBricks(volume.dims(), int(voxelTypeSize(volume.type())), maxTextureSize, budgetBytes);
    scaleOffset_ = volumeTextureScaleOffset(volume.type());
    volume_ = &volume;
    generation_ = generation;
    uploads_ = bytes_ = 0;
    pool_.resize(std::min(layout_.resident, layout_.bricks.size()));
    for (GlTexture& t : pool_) t = GlTexture::make();
    holder_.assign(pool_.size(), -1);
    lastUse_.assign(pool_.size(), -1);
    slotOf_.assign(layout_.bricks.size(), -1);
    if (pool_.size() == layout_.bricks.size())  // all resident: upload once, now
        for (int b = 0; b < int(layout_.bricks.size()); ++b) texture(b);
}

unsigned VolumeTextures::texture(int brick) {
    int slot = slotOf_[std::size_t(brick)];
    if (slot < 0) {
        slot = int(std::min_element(lastUse_.begin(), lastUse_.end()) - lastUse_.begin());
        if (holder_[std::size_t(slot)] >= 0) slotOf_[std::size_t(holder_[std::size_t(slot)])] = -1;
        const VolumeBrick& b = layout_.bricks[std::size_t(brick)];
        uploadVolumeBox(pool_[std::size_t(slot)], *volume_, b.textureOrigin, b.textureSize);
        holder_[std::size_t(slot)] = brick;
        slotOf_[std::size_t(brick)] = slot;
        ++uploads_;
        bytes_ += b.bytes;
    }
    lastUse_[std::size_t(slot)] = ++clock_;
    return pool_[std::size_t(slot)];
}

}  // namespace voxlab
