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
    ahead_.clear();
}

void VolumeTextures::set(const Volume& volume, unsigned long generation, std::size_t budgetBytes, int maxTextureSize) {
    if (volume_ == &volume && generation_ == generation && layout_.budgetBytes == budgetBytes && !pool_.empty()) return;
    release();
    layout_ = planBricks(volume.dims(), int(voxelTypeSize(volume.type())), maxTextureSize, budgetBytes,
                         residentBricksAimed(volume.bytes().size(), budgetBytes, passesExpensive_));
    scaleOffset_ = volumeTextureScaleOffset(volume.type());
    volume_ = &volume;
    generation_ = generation;
    pool_.resize(std::min(layout_.resident, layout_.bricks.size()));
    for (GlTexture& t : pool_) t = GlTexture::make();
    holder_.assign(pool_.size(), -1);
    lastUse_.assign(pool_.size(), -1);
    slotOf_.assign(layout_.bricks.size(), -1);
    ahead_.assign(layout_.bricks.size(), -1);
    if (pool_.size() == layout_.bricks.size())  // all resident: upload once, now
        for (int b = 0; b < int(layout_.bricks.size()); ++b) texture(b);
}

void VolumeTextures::beginFrame(const std::vector<int>& order) {
    std::fill(ahead_.begin(), ahead_.end(), -1);
    for (std::size_t i = 0; i < order.size(); ++i) ahead_[std::size_t(order[i])] = int(i);
    frameStart_ = clock_ + 1;
}

// The slot a missing brick takes (the rule is in volume_textures.h).
int VolumeTextures::slotToFill() const {
    int stale = -1, drawn = -1, furthest = -1;
    for (int s = 0; s < int(pool_.size()); ++s) {
        const int brick = holder_[std::size_t(s)];
        if (brick < 0) return s;
        const long used = lastUse_[std::size_t(s)];
        const int ahead = ahead_[std::size_t(brick)];
        if (ahead >= 0) {
            if (furthest < 0 || ahead > ahead_[std::size_t(holder_[std::size_t(furthest)])]) furthest = s;
        } else if (used < frameStart_) {
            if (stale < 0 || used < lastUse_[std::size_t(stale)]) stale = s;
        } else if (drawn < 0 || used > lastUse_[std::size_t(drawn)]) {
            drawn = s;
        }
    }
    return stale >= 0 ? stale : drawn >= 0 ? drawn : furthest;
}

unsigned VolumeTextures::texture(int brick) {
    int slot = slotOf_[std::size_t(brick)];
    if (slot < 0) {
        slot = slotToFill();
        if (holder_[std::size_t(slot)] >= 0) slotOf_[std::size_t(holder_[std::size_t(slot)])] = -1;
        const VolumeBrick& b = layout_.bricks[std::size_t(brick)];
        uploadVolumeBox(pool_[std::size_t(slot)], *volume_, b.textureOrigin, b.textureSize);
        holder_[std::size_t(slot)] = brick;
        slotOf_[std::size_t(brick)] = slot;
        ++uploads_;
        bytes_ += b.bytes;
    }
    lastUse_[std::size_t(slot)] = ++clock_;
    ahead_[std::size_t(brick)] = -1;
    return pool_[std::size_t(slot)];
}

}  // namespace voxlab
