// voxlab internals: the ray profile's classification of a sample when the
// scene has a label map or a fused second volume (scene.h), as the composite
// renderer classifies with them (reference/labels/README.md,
// shaders/voxlab/labels.glsl and fusion.glsl), in double on the CPU.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/scene.h"
#include "voxlab/transfer_function.h"
#include "voxlab/volume.h"
#include "volume_reader.h"

namespace voxlab {

class ProfileSceneClassifier {
public:
    // Null when the scene has neither; throws voxlab::Error as the renderer
    // would for a label map that does not fit. `sceneFunction` is the
    // transfer function the renderer classifies with.
    static std::unique_ptr<ProfileSceneClassifier> make(const Scene& scene, const Volume& volume,
                                                        const TransferFunction& sceneFunction);
    // Colour (not premultiplied) and opacity per unit length of the sample
    // at p whose interpolated value (first volume) is `value`.
    glm::dvec4 classify(const glm::dvec3& p, double value) const;

private:
    ProfileSceneClassifier(const Scene& scene, const Volume& volume, const TransferFunction& sceneFunction);
    glm::dvec4 classifyLabel(int label, double value) const;
    int labelAt(glm::ivec3 ijk) const;
    glm::dvec4 labelled(const glm::dvec3& p, double value) const;
    glm::dvec4 fused(const glm::dvec3& p, double value) const;

    const Scene& scene_;
    const Volume& volume_;
    const TransferFunction& sceneFunction_;
    std::vector<std::uint16_t> labels_;
    std::optional<Volume> distance_, second_;
    std::optional<TransferFunction> secondFunction_;
    std::unique_ptr<VolumeReader> distanceReader_, secondReader_;
};

}  // namespace voxlab
