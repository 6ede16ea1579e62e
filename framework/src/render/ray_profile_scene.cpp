// voxlab: the ray profile's classification with a label map or a fused
// second volume (see ray_profile_scene.h). Written from the labels handout
// and scene.h, not from the shaders.
#include "ray_profile_scene.h"

#include <algorithm>
#include <cstring>

#include "voxlab/label_map.h"

namespace voxlab {

std::unique_ptr<ProfileSceneClassifier> ProfileSceneClassifier::make(const Scene& scene, const Volume& volume,
                                                                     const TransferFunction& sceneFunction) {
    if (!scene.labels && !scene.fusion) return nullptr;
    return std::unique_ptr<ProfileSceneClassifier>(new ProfileSceneClassifier(scene, volume, sceneFunction));
}

ProfileSceneClassifier::ProfileSceneClassifier(const Scene& scene, const Volume& volume,
                                               const TransferFunction& sceneFunction)
    : scene_(scene), volume_(volume), sceneFunction_(sceneFunction) {
    if (scene.labels) {
        labels_ = checkedLabels(loadVolume(scene.labels->volume), volume);
        if (scene.labels->distance) {
            const std::vector<float> d =
                distanceToLabel(labels_, volume.dims(), volume.spacing(), scene.labels->distance->to);
            std::vector<std::uint8_t> bytes(d.size() * sizeof(float));
            std::memcpy(bytes.data(), d.data(), bytes.size());
            distance_.emplace(volume.dims(), VoxelType::Float32, volume.spacing(), std::move(bytes), "distance");
            distanceReader_ = std::make_unique<VolumeReader>(*distance_, Interpolation::Trilinear);  // a texture
        }
    } else {
        second_.emplace(loadVolume(scene.fusion->dataset));
        // The second volume is read nearest or trilinearly (fusion.glsl), whatever the first's interpolation.
        secondReader_ = std::make_unique<VolumeReader>(
            *second_, scene.interpolation == Interpolation::Nearest ? Interpolation::Nearest : Interpolation::Trilinear);
        secondFunction_ = scene.fusion->transferFunction
                              ? *scene.fusion->transferFunction
                              : defaultCompositingFunction(scene.fusion->window.value_or(second_->valueRange()));
    }
}

int ProfileSceneClassifier::labelAt(glm::ivec3 ijk) const {
    const glm::ivec3 d = volume_.dims();
    ijk = glm::clamp(ijk, glm::ivec3(0), d - 1);
    return labels_[std::size_t(ijk.x) + std::size_t(d.x) * (std::size_t(ijk.y) + std::size_t(d.y) * std::size_t(ijk.z))];
}

glm::dvec4 ProfileSceneClassifier::classifyLabel(int label, double value) const {
    const LabelClass* c = scene_.labels->find(label);
    if (c && !c->visible) return glm::dvec4(0.0);
    const TransferFunction& f = c && c->transferFunction ? *c->transferFunction : sceneFunction_;
    return glm::dvec4(f.evaluate(value));
}

glm::dvec4 ProfileSceneClassifier::labelled(const glm::dvec3& p, double value) const {
    const glm::dvec3 u = p / volume_.spacing();
    const int nearest = labelAt(glm::ivec3(glm::floor(u)));
    glm::dvec4 c;
    if (scene_.labels->sampling == LabelSampling::Nearest) {
        c = classifyLabel(nearest, value);
    } else {  // each label's mask interpolated: the 8 voxels with their weights
        const glm::dvec3 shifted = u - 0.5, lower = glm::floor(shifted), w = shifted - lower;
        glm::dvec4 sum(0.0);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
            const double weight = (o.x ? w.x : 1 - w.x) * (o.y ? w.y : 1 - w.y) * (o.z ? w.z : 1 - w.z);
            const glm::dvec4 k = classifyLabel(labelAt(glm::ivec3(lower) + o), value);
            sum += weight * glm::dvec4(glm::dvec3(k) * k.a, k.a);
        }
        c = sum.a > 0.0 ? glm::dvec4(glm::dvec3(sum) / sum.a, sum.a) : glm::dvec4(0.0);
    }
    const std::optional<LabelDistance>& d = scene_.labels->distance;
    if (!d || c.a <= 0.0) return c;
    const bool applies = d->applyTo.empty()
                             ? nearest != d->to
                             : std::find(d->applyTo.begin(), d->applyTo.end(), nearest) != d->applyTo.end();
    if (!applies) return c;
    const glm::dvec4 f(d->transferFunction.evaluate(distanceReader_->sample(p)));
    return {glm::dvec3(f), c.a * f.a};
}

glm::dvec4 ProfileSceneClassifier::fused(const glm::dvec3& p, double value) const {
    const Fusion& f = *scene_.fusion;
    const glm::dvec4 a(sceneFunction_.evaluate(value));
    const glm::dvec4 b(secondFunction_->evaluate(secondReader_->sample(p / volume_.extent() * second_->extent())));
    switch (f.mode) {
        case FusionMode::Checkerboard: {
            const glm::ivec3 cell(glm::floor(p / (f.checkerSize * volume_.minSpacing())));
            return ((cell.x + cell.y + cell.z) & 1) == 0 ? a : b;
        }
        case FusionMode::Split: {
            const glm::dvec3 point = f.splitPoint.value_or(glm::dvec3(volume_.dims()) * 0.5) * volume_.spacing();
            return glm::dot(p - point, glm::normalize(f.splitNormal)) >= 0.0 ? a : b;
        }
        case FusionMode::ColorOpacity: return {glm::dvec3(b), a.a};
        case FusionMode::Sum: break;
    }
    const double total = a.a + b.a;
    const glm::dvec3 colour = total > 0.0 ? (a.a * glm::dvec3(a) + b.a * glm::dvec3(b)) / total : glm::dvec3(0.0);
    return {colour, std::min(total, 1.0)};
}

glm::dvec4 ProfileSceneClassifier::classify(const glm::dvec3& p, double value) const {
    return scene_.labels ? labelled(p, value) : fused(p, value);
}

}  // namespace voxlab
