// voxlab: a scene's label map and second volume on the GPU (see
// scene_volumes.h).
//
// Label lookups are two texture reads: the label's row (u_label_rows, one
// texel per label value, 4096 per texture row) and that row's transfer
// function (u_label_tf, one row per class, all baked to one size over the
// dataset's value range). The label volume itself is an unsigned integer
// texture, read with texelFetch only: integer textures cannot be filtered,
// which is exactly right for categories.
#include "voxlab/scene_volumes.h"

#include <algorithm>

#include "voxlab/error.h"
#include "voxlab_gl.h"

namespace voxlab {
namespace {

// Texture units, after the precomputed textures (6 and 7) and the cubic
// coefficients (9).
constexpr int kLabelUnit = 10, kRowUnit = 11, kLabelTfUnit = 12, kDistanceUnit = 13, kSecondUnit = 14,
              kSecondTfUnit = 15;
constexpr int kRowLength = 4096;  // label values per texture row of u_label_rows

void textureParameters(GLenum target, GLint filter) {
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, filter);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(target, wrap, GL_CLAMP_TO_EDGE);
}

void bindUnit(int unit, GLenum target, unsigned texture) {
    glActiveTexture(GL_TEXTURE0 + GLenum(unit));
    glBindTexture(target, texture);
}

// A key that changes whenever a transfer function's points do.
std::string functionKey(const TransferFunction& f) {
    std::string key;
    for (const ControlPoint& p : f.points())
        key += std::to_string(p.value) + "," + std::to_string(p.color.r) + "," + std::to_string(p.color.g) + "," +
               std::to_string(p.color.b) + "," + std::to_string(p.alpha) + ";";
    return key;
}

// The range a table over distances spans: the function's own points (it is
// constant outside them), never empty.
glm::dvec2 pointRange(const TransferFunction& f) {
    const double lo = f.points().front().value, hi = f.points().back().value;
    return {lo, hi > lo ? hi : lo + 1.0};
}

}  // namespace

glm::vec2 uploadVolumeTexture(unsigned texture, const Volume& volume) {
    return uploadVolumeBox(texture, volume, glm::ivec3(0), volume.dims());
}

glm::vec2 volumeTextureScaleOffset(VoxelType type) {
    switch (type) {
        case VoxelType::UInt8: return {255.0f, 0.0f};
        case VoxelType::UInt16: return {65535.0f, 0.0f};
        case VoxelType::Int16: return {65535.0f, -32768.0f};
        case VoxelType::Float32: break;
    }
    return {1.0f, 0.0f};
}

// A box whose voxels are converted on the way (`convert`: a voxel's value
// as an int -> a texel of type Out), one z-slice at a time, into a texture
// of `internalFormat` with texels of `type`. The unpack state is reset: the
// slices are packed.
template <class In, class Out, class Convert>
void uploadConvertedSlices(const Volume& volume, const glm::ivec3& origin, const glm::ivec3& size, GLenum internalFormat,
                           GLenum type, Convert convert) {
    const glm::ivec3 d = volume.dims();
    glTexImage3D(GL_TEXTURE_3D, 0, internalFormat, size.x, size.y, size.z, 0, GL_RED, type, nullptr);
    for (GLenum name : {GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS,
                        GL_UNPACK_SKIP_IMAGES})
        glPixelStorei(name, 0);
    std::vector<Out> slice(std::size_t(size.x) * std::size_t(size.y));
    const auto* src = static_cast<const In*>(volume.data());
    for (int z = 0; z < size.z; ++z) {
        for (int y = 0; y < size.y; ++y) {
            const In* row = src + (std::size_t(origin.z + z) * d.y + std::size_t(origin.y + y)) * d.x + origin.x;
            for (int x = 0; x < size.x; ++x) slice[std::size_t(y) * size.x + x] = convert(int(row[x]));
        }
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, z, size.x, size.y, 1, GL_RED, type, slice.data());
        volume.releaseSlices(origin.z + z, origin.z + z + 1);  // a streamed volume's page by page
    }
}

// A streamed volume's box (uint8, uint16, float32), a slab of z-slices at a
// time, each slab's pages let go once it is up: the file's pages resident
// at once are one slab's, not the box's slices whole (a brick half as wide
// as the volume reads every page of its slices). The unpack state picks the
// box's rows as for a volume in memory.
namespace {

void uploadStreamedBox(const Volume& volume, const glm::ivec3& origin, const glm::ivec3& size) {
    const GLenum internal = volume.type() == VoxelType::UInt8 ? GL_R8 : volume.type() == VoxelType::UInt16 ? GL_R16 : GL_R32F;
    const GLenum type = volume.type() == VoxelType::UInt8 ? GL_UNSIGNED_BYTE
                        : volume.type() == VoxelType::UInt16 ? GL_UNSIGNED_SHORT : GL_FLOAT;
    glTexImage3D(GL_TEXTURE_3D, 0, GLint(internal), size.x, size.y, size.z, 0, GL_RED, type, nullptr);
    const std::size_t slice = std::size_t(volume.dims().x) * std::size_t(volume.dims().y) * voxelTypeSize(volume.type());
    const int slab = int(std::max<std::size_t>(1, (std::size_t(16) << 20) / slice));
    for (int z = 0; z < size.z; z += slab) {
        const int n = std::min(slab, size.z - z);
        glPixelStorei(GL_UNPACK_SKIP_IMAGES, origin.z + z);
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, z, size.x, size.y, n, GL_RED, type, volume.data());
        volume.releaseSlices(origin.z + z, origin.z + z + n);
    }
}

}  // namespace

// Straight from the volume's memory: the unpack state picks the box's rows
// out of the whole volume, so no copy of the box is made (int16 is shifted
// one z-slice at a time).
glm::vec2 uploadVolumeBox(unsigned texture, const Volume& volume, const glm::ivec3& origin, const glm::ivec3& size) {
    const glm::ivec3 d = volume.dims();
    glBindTexture(GL_TEXTURE_3D, texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, d.x);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, d.y);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, origin.x);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, origin.y);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, origin.z);
    // WebGL 2 has no 16-bit normalised textures (only with EXT_texture_norm16,
    // which software renderers lack): there 16-bit data goes up as R32F
    // holding the same normalised values, (v + shift) / 65535, exactly (16
    // bits fit a float's 24-bit mantissa). Twice the memory, the same numbers
    // in every shader. (Hardware filtering of R32F needs
    // OES_texture_float_linear; the explicit trilinear path never needs it.)
    if (volume.streamed() && volume.type() != VoxelType::Int16) {
        uploadStreamedBox(volume, origin, size);
    } else switch (volume.type()) {
        case VoxelType::UInt8:
            glTexImage3D(GL_TEXTURE_3D, 0, GL_R8, size.x, size.y, size.z, 0, GL_RED, GL_UNSIGNED_BYTE, volume.data());
            break;
        case VoxelType::UInt16:
#ifdef __EMSCRIPTEN__
            uploadConvertedSlices<std::uint16_t, float>(volume, origin, size, GL_R32F, GL_FLOAT,
                                                        [](int v) { return float(v) / 65535.0f; });
#else
            glTexImage3D(GL_TEXTURE_3D, 0, GL_R16, size.x, size.y, size.z, 0, GL_RED, GL_UNSIGNED_SHORT, volume.data());
#endif
            break;
        case VoxelType::Int16:
            // R16_SNORM would merge -32768 and -32767; shifting keeps every value.
#ifdef __EMSCRIPTEN__
            uploadConvertedSlices<std::int16_t, float>(volume, origin, size, GL_R32F, GL_FLOAT,
                                                       [](int v) { return float(v + 32768) / 65535.0f; });
#else
            uploadConvertedSlices<std::int16_t, std::uint16_t>(volume, origin, size, GL_R16, GL_UNSIGNED_SHORT,
                                                               [](int v) { return std::uint16_t(v + 32768); });
#endif
            break;
        case VoxelType::Float32:
            glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, size.x, size.y, size.z, 0, GL_RED, GL_FLOAT, volume.data());
            break;
    }
    for (GLenum name : {GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS,
                        GL_UNPACK_SKIP_IMAGES})
        glPixelStorei(name, 0);
    volume.releaseSlices(origin.z, origin.z + size.z);  // a streamed volume's: read again when needed
    textureParameters(GL_TEXTURE_3D, GL_NEAREST);
    checkGlError("uploading a volume texture");
    return volumeTextureScaleOffset(volume.type());
}

void uploadTableTexture(unsigned texture, const TransferFunctionTable& table) {
    const int width = std::min(table.size, kTransferFunctionRowLength);
    const int rows = (table.size + width - 1) / width;
    std::vector<glm::vec4> texels(std::size_t(width) * rows, table.rgba.back());
    std::copy(table.rgba.begin(), table.rgba.end(), texels.begin());
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, rows, 0, GL_RGBA, GL_FLOAT, texels.data());
    // The shader fetches and interpolates entries itself: no filtering.
    textureParameters(GL_TEXTURE_2D, GL_NEAREST);
    checkGlError("uploading a transfer function");
}

SceneVolumes::SceneVolumes() {
    for (GlTexture* t : {&labelTexture_, &rowTexture_, &labelTfTexture_, &distanceTexture_, &distanceTfTexture_,
                         &secondTexture_, &secondTfTexture_})
        *t = GlTexture::make();
}

SceneVolumes::~SceneVolumes() = default;

void SceneVolumes::prepare(const Scene& scene, const Volume& volume, unsigned long volumeGeneration,
                           const TransferFunction* sceneFunction) {
    if (scene.labels && scene.fusion)
        throw Error("a scene shows either a label map or a fused second volume, not both");
    if (scene.labels) {
        const TransferFunction fallback = defaultCompositingFunction(scene.window.value_or(volume.valueRange()));
        prepareLabels(*scene.labels, volume, volumeGeneration, sceneFunction ? *sceneFunction : fallback);
    }
    if (scene.fusion) prepareFusion(*scene.fusion);
}

void SceneVolumes::prepareLabels(const LabelMap& map, const Volume& volume, unsigned long volumeGeneration,
                                 const TransferFunction& sceneFunction) {
    if (map.volume != labelPath_ || labelsCheckedFor_ != volumeGeneration) {
        labelPath_.clear();  // a failed load leaves nothing half-checked behind
        const Volume file = loadVolume(map.volume);
        labels_ = checkedLabels(file, volume);
        largestLabel_ = labels_.empty() ? 0 : int(*std::max_element(labels_.begin(), labels_.end()));
        const glm::ivec3 d = volume.dims();
        glBindTexture(GL_TEXTURE_3D, labelTexture_);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
        glTexImage3D(GL_TEXTURE_3D, 0, GL_R16UI, d.x, d.y, d.z, 0, GL_RED_INTEGER, GL_UNSIGNED_SHORT, labels_.data());
        textureParameters(GL_TEXTURE_3D, GL_NEAREST);
        checkGlError("uploading the label map");
        labelPath_ = map.volume;
        labelsCheckedFor_ = volumeGeneration;
        tablesKey_.clear();
        distanceKey_.clear();
    }
    uploadLabelTables(map, volume, sceneFunction);
    if (map.distance) uploadDistance(map, volume);
}

void SceneVolumes::uploadLabelTables(const LabelMap& map, const Volume& volume,
                                     const TransferFunction& sceneFunction) {
    const LabelRows rows = labelRows(map, sceneFunction, largestLabel_);
    std::string key = std::to_string(volume.minValue()) + ":" + std::to_string(volume.maxValue()) + "|";
    for (const glm::vec2& r : rows.rows) key += std::to_string(r.x) + "," + std::to_string(r.y) + ";";
    for (const TransferFunction* f : rows.tables) key += "|" + functionKey(*f);
    if (key == tablesKey_) return;
    // Rows of one size: the finest any function needs to stay within half a
    // grey level (TransferFunction::bake), at most one texture row.
    const glm::dvec2 range = volume.valueRange();
    int size = 0;  // 2 for a constant volume, else a power of two from 256
    for (const TransferFunction* f : rows.tables)
        size = std::max(size, f->bake(range.x, range.y, 0.5 / 255.0, kTransferFunctionRowLength).size);
    std::vector<glm::vec4> texels;
    unionTable_ = TransferFunctionTable{};
    for (const TransferFunction* f : rows.tables) {
        TransferFunctionTable t = f->bake(range.x, range.y, -1.0, size);  // exactly `size` entries
        texels.insert(texels.end(), t.rgba.begin(), t.rgba.end());
        if (unionTable_.size == 0) unionTable_ = t;
        for (int i = 0; i < t.size; ++i) unionTable_.rgba[i].a = std::max(unionTable_.rgba[i].a, t.rgba[i].a);
    }
    labelRange_ = {unionTable_.lo, unionTable_.hi};
    labelTableSize_ = size;
    glBindTexture(GL_TEXTURE_2D, labelTfTexture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, size, GLsizei(rows.tables.size()), 0, GL_RGBA, GL_FLOAT, texels.data());
    textureParameters(GL_TEXTURE_2D, GL_NEAREST);
    // The row of each label value, kRowLength values per texture row.
    const int count = int(rows.rows.size());
    const int width = std::min(count, kRowLength), height = (count + kRowLength - 1) / kRowLength;
    std::vector<glm::vec2> rowTexels(std::size_t(width) * height, glm::vec2(0.0f));
    std::copy(rows.rows.begin(), rows.rows.end(), rowTexels.begin());
    glBindTexture(GL_TEXTURE_2D, rowTexture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, width, height, 0, GL_RG, GL_FLOAT, rowTexels.data());
    textureParameters(GL_TEXTURE_2D, GL_NEAREST);
    checkGlError("uploading the label tables");
    tablesKey_ = key;
}

void SceneVolumes::uploadDistance(const LabelMap& map, const Volume& volume) {
    const LabelDistance& d = *map.distance;
    const std::string key = std::to_string(d.to) + "|" + functionKey(d.transferFunction);
    if (key == distanceKey_) return;
    const std::vector<float> field = distanceToLabel(labels_, volume.dims(), volume.spacing(), d.to);
    const glm::ivec3 n = volume.dims();
    glBindTexture(GL_TEXTURE_3D, distanceTexture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, n.x, n.y, n.z, 0, GL_RED, GL_FLOAT, field.data());
    textureParameters(GL_TEXTURE_3D, GL_LINEAR);
    distanceRange_ = pointRange(d.transferFunction);
    const TransferFunctionTable table = d.transferFunction.bake(distanceRange_.x, distanceRange_.y);
    distanceTableSize_ = table.size;
    uploadTableTexture(distanceTfTexture_, table);
    checkGlError("uploading the label distance field");
    distanceKey_ = key;
}

// The same voxels as float32, in data units. The second volume is filtered
// by the GPU, which filters a float texture in float; an 8-bit one llvmpipe
// filters in 8-bit fixed point, 20 grey levels off at a steep transfer
// function's edge.
static Volume inFloat(const Volume& volume) {
    if (volume.type() == VoxelType::Float32) return volume;
    std::vector<std::uint8_t> bytes(volume.voxelCount() * sizeof(float));
    auto* values = reinterpret_cast<float*>(bytes.data());
    for (std::size_t i = 0; i < volume.voxelCount(); ++i) values[i] = float(volume.valueAt(i));
    return Volume(volume.dims(), VoxelType::Float32, volume.spacing(), std::move(bytes), volume.name());
}

void SceneVolumes::prepareFusion(const Fusion& fusion) {
    if (fusion.dataset != secondPath_ || !second_) {
        secondPath_.clear();
        second_ = std::make_unique<Volume>(inFloat(loadVolume(fusion.dataset)));
        const glm::vec2 so = uploadVolumeTexture(secondTexture_, *second_);
        // The GPU interpolates the second volume (fusion.glsl), in float:
        // texelFetch, for nearest, ignores the filter.
        glBindTexture(GL_TEXTURE_3D, secondTexture_);
        textureParameters(GL_TEXTURE_3D, GL_LINEAR);
        secondScale_ = so.x, secondOffset_ = so.y;
        secondPath_ = fusion.dataset;
        secondTfKey_.clear();
    }
    const glm::dvec2 window = fusion.window.value_or(second_->valueRange());
    const TransferFunction f = fusion.transferFunction ? *fusion.transferFunction : defaultCompositingFunction(window);
    const std::string key = functionKey(f);
    if (key == secondTfKey_) return;
    const glm::dvec2 range = second_->valueRange();
    secondTable_ = f.bake(range.x, range.y);
    uploadTableTexture(secondTfTexture_, secondTable_);
    secondTfKey_ = key;
}

void SceneVolumes::addConstants(const Scene& scene, ShaderConstants* constants) const {
    (*constants)["u_labelled"] = scene.labels ? 1 : 0;
    (*constants)["u_label_masks"] = scene.labels && scene.labels->sampling == LabelSampling::Masks ? 1 : 0;
    (*constants)["u_label_distance_on"] = scene.labels && scene.labels->distance ? 1 : 0;
    (*constants)["u_fused"] = scene.fusion ? 1 : 0;
    (*constants)["u_fusion_mode"] = scene.fusion ? int(scene.fusion->mode) : 0;
}

void SceneVolumes::bind(const ShaderProgram& prog, const Scene& scene, const Volume& volume) const {
    // Every sampler gets its own unit even when unused: two samplers of
    // different types on one unit (the default, 0) make a draw invalid.
    prog.set("u_labels", kLabelUnit);
    prog.set("u_label_rows", kRowUnit);
    prog.set("u_label_tf", kLabelTfUnit);
    prog.set("u_label_distance", kDistanceUnit);
    prog.set("u_distance_tf", kSecondTfUnit);
    prog.set("u_volume2", kSecondUnit);
    prog.set("u_tf2", kSecondTfUnit);
    if (scene.labels) {
        bindUnit(kLabelUnit, GL_TEXTURE_3D, labelTexture_);
        bindUnit(kRowUnit, GL_TEXTURE_2D, rowTexture_);
        bindUnit(kLabelTfUnit, GL_TEXTURE_2D, labelTfTexture_);
        prog.set("u_label_count", largestLabel_ + 1);
        prog.set("u_label_tf_size", labelTableSize_);
        prog.set("u_label_tf_range", glm::vec2(labelRange_));
        if (scene.labels->distance) {
            bindUnit(kDistanceUnit, GL_TEXTURE_3D, distanceTexture_);
            bindUnit(kSecondTfUnit, GL_TEXTURE_2D, distanceTfTexture_);
            prog.set("u_distance_tf_size", distanceTableSize_);
            prog.set("u_distance_tf_range", glm::vec2(distanceRange_));
        }
    }
    if (scene.fusion) {
        const Fusion& f = *scene.fusion;
        bindUnit(kSecondUnit, GL_TEXTURE_3D, secondTexture_);
        bindUnit(kSecondTfUnit, GL_TEXTURE_2D, secondTfTexture_);
        prog.set("u_volume2_dims", second_->dims());
        prog.set("u_value2_scale", secondScale_);
        prog.set("u_value2_offset", secondOffset_);
        prog.set("u_tf2_size", secondTable_.size);
        prog.set("u_tf2_range", glm::vec2(float(secondTable_.lo), float(secondTable_.hi)));
        prog.set("u_fusion_checker", float(f.checkerSize * volume.minSpacing()));
        const glm::dvec3 point = f.splitPoint.value_or(glm::dvec3(volume.dims()) * 0.5) * volume.spacing();
        prog.set("u_fusion_point", glm::vec3(point));
        prog.set("u_fusion_normal", glm::vec3(glm::normalize(f.splitNormal)));
    }
}

}  // namespace voxlab
