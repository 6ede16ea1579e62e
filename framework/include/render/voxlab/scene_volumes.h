// voxlab: the volumes a scene brings besides its dataset, on the GPU: a
// label map with its per-label transfer functions and distance field
// (scene "labels"), and a second scalar volume to fuse with the first
// (scene "fusion"). The render engine owns one and asks it before each pass.
//
// Files are loaded once per path and checked against the dataset (a label
// map must match its grid: label_map.h); the textures are made again only
// when what they come from changes (the file, the dataset, a transfer
// function, the classes). Shaders read them through voxlab/labels.glsl and
// voxlab/fusion.glsl:
//   u_labels (usampler3D), u_label_rows, u_label_tf, u_label_tf_size,
//   u_label_tf_range, u_label_distance, u_distance_tf, u_distance_tf_size,
//   u_distance_tf_range; u_volume2, u_volume2_dims, u_value2_scale,
//   u_value2_offset, u_tf2, u_tf2_size, u_tf2_range, u_fusion_checker,
//   u_fusion_point, u_fusion_normal.
// and the switches, baked into programs: u_labelled, u_label_masks,
// u_label_distance_on, u_fused, u_fusion_mode.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "voxlab/gl_object.h"
#include "voxlab/label_map.h"
#include "voxlab/scene.h"
#include "voxlab/shader.h"
#include "voxlab/transfer_function.h"
#include "voxlab/volume.h"

namespace voxlab {

class SceneVolumes {
public:
    SceneVolumes();
    ~SceneVolumes();
    SceneVolumes(const SceneVolumes&) = delete;
    SceneVolumes& operator=(const SceneVolumes&) = delete;

    // Loads and checks what `scene` names besides its dataset (`volume`) and
    // brings the textures up to date; `sceneFunction` is the transfer
    // function the pass classifies with (the scene's, or the engine's
    // fallback), row 0 of the label table. Throws voxlab::Error with one
    // line for a label map that does not fit, a missing file, ...
    // `volumeGeneration` changes whenever the engine's volume does.
    void prepare(const Scene& scene, const Volume& volume, unsigned long volumeGeneration,
                 const TransferFunction* sceneFunction);
    // The switches to bake into a program for that scene.
    void addConstants(const Scene& scene, ShaderConstants* constants) const;
    // Binds the textures (units 10 to 15) and sets the uniforms above.
    void bind(const ShaderProgram& program, const Scene& scene, const Volume& volume) const;

    // For empty-space skipping with a label map: per entry, the largest
    // opacity of any row (a brick is empty only if no label can show in it).
    const TransferFunctionTable& labelUnionTable() const { return unionTable_; }
    // The label values of the current label map (empty without one).
    const std::vector<std::uint16_t>& labels() const { return labels_; }
    const Volume* second() const { return second_.get(); }

private:
    void prepareLabels(const LabelMap& map, const Volume& volume, unsigned long volumeGeneration,
                       const TransferFunction& sceneFunction);
    void uploadLabelTables(const LabelMap& map, const Volume& volume, const TransferFunction& sceneFunction);
    void uploadDistance(const LabelMap& map, const Volume& volume);
    void prepareFusion(const Fusion& fusion);

    // The label map: its file, the dataset it was checked against, its values.
    std::string labelPath_;
    unsigned long labelsCheckedFor_ = 0;
    std::vector<std::uint16_t> labels_;
    int largestLabel_ = 0;
    std::string tablesKey_, distanceKey_;
    TransferFunctionTable unionTable_;
    glm::dvec2 labelRange_{0.0};
    int labelTableSize_ = 0;
    glm::dvec2 distanceRange_{0.0};
    int distanceTableSize_ = 0;
    // The second volume and its classification.
    std::string secondPath_;
    std::unique_ptr<Volume> second_;
    float secondScale_ = 1.0f, secondOffset_ = 0.0f;
    std::string secondTfKey_;
    TransferFunctionTable secondTable_;

    GlTexture labelTexture_, rowTexture_, labelTfTexture_, distanceTexture_, distanceTfTexture_, secondTexture_,
        secondTfTexture_;
};

// Uploads `volume` as a 3D texture in its native precision (R8, R16, R32F;
// int16 shifted by +32768 into R16 so that no value is lost) and returns the
// (scale, offset) that turns a texel back into a data value.
glm::vec2 uploadVolumeTexture(unsigned texture, const Volume& volume);
// The same for the box of `size` voxels at `origin` (a brick with its apron).
// The shader reads texel t in [0,1] and recovers the data value as
// t*scale + offset (volumeTextureScaleOffset), so every renderer works in
// the data's own units.
glm::vec2 volumeTextureScaleOffset(VoxelType type);
glm::vec2 uploadVolumeBox(unsigned texture, const Volume& volume, const glm::ivec3& origin, const glm::ivec3& size);

// Uploads a baked transfer-function table to a 2D texture, row-major,
// kTransferFunctionRowLength entries per row (see transfer_function.h).
void uploadTableTexture(unsigned texture, const TransferFunctionTable& table);

}  // namespace voxlab
