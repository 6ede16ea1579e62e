// voxlab: the built-in renderers. Each is declared here and defined in its
// own file under framework/src/renderers/ (ID_renderer.cpp); its GLSL entry
// point is shaders/renderers/ID.frag and its stage code is reference/ID/.
#pragma once

#include <memory>
#include <mutex>

#include "voxlab/renderer.h"

namespace voxlab {

// What the ray profile stops at for compositing (shared_parameters.cpp),
// from compositingParameters().
ProfileSettings compositingProfileSettings(const ParameterValues& values);

class SlicerRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::FirstHit; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
};

class MipRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::Largest; }
    std::string id() const override;
    std::string description() const override;
    ProfileModel profileModel() const override { return ProfileModel::Maximum; }
};

// The renderer of a ray-value stage: a stage whose function
// `float <stage>_ray(Ray ray)` (in <stage>/<stage>.glsl) returns one value
// per ray in data units, shown through the window or the transfer function
// (MinIP, the average, ...). Its entry shader is made from
// shaders/renderers/ray_value.frag.in with the stage's name filled in, and
// its parameters become uniforms u_NAME; so adding such a stage takes its
// folder and one line in renderer_registry.cpp, e.g.
//   r.add<RayValueRenderer>("minip", "minimum intensity projection: ...", ProfileModel::Minimum);
// What a ray-value stage's function returns: one value, in data units,
// shown through the window or the transfer function (float STAGE_ray(Ray));
// or a colour, premultiplied, with its opacity (vec4 STAGE_ray(Ray)), which
// classifies with the transfer function (a grey ramp when the scene has
// none).
enum class RayResult { Value, Colour };

class RayValueRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues& values) const override;
    RayValueRenderer(std::string stage, std::string description, ProfileModel profile = ProfileModel::None,
                     std::vector<ParameterSpec> parameters = {}, RayResult result = RayResult::Value);
    bool needsTransferFunction() const override { return result_ == RayResult::Colour; }
    std::string id() const override { return stage_; }
    std::string description() const override { return description_; }
    std::vector<ParameterSpec> parameters() const override { return parameters_; }
    ProfileModel profileModel() const override { return profile_; }
    std::map<std::string, std::string> generatedShaders() const override;

private:
    std::string stage_, description_;
    ProfileModel profile_;
    std::vector<ParameterSpec> parameters_;
    RayResult result_;
};

class FirstHitRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::FirstHit; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
    ProfileModel profileModel() const override { return ProfileModel::FirstHit; }
    ProfileSettings profileSettings(const ParameterValues& values) const override;
};

class SlabMipRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::Largest; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    ProfileModel profileModel() const override { return ProfileModel::Maximum; }
};

class CompositeRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues& values) const override;
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool needsTransferFunction() const override { return true; }
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
    ProfileModel profileModel() const override { return ProfileModel::Composite; }
    ProfileSettings profileSettings(const ParameterValues& values) const override {
        return compositingProfileSettings(values);
    }
    std::vector<Precomputation> precomputations(const Scene& scene, const Volume& volume,
                                                const ParameterValues& values) const override;
    void checkScene(const Scene& scene, const ParameterValues& values) const override;
};

// The pre-integration table's size, texels on each axis (the preintegration
// stage's PREINTEGRATION_TABLE_SIZE).
constexpr int kPreintegrationTableSize = 256;
// The light volume of the shadows stage: the volume's dimensions, at most
// `resolution` voxels on each axis (composite's `shadow_resolution`).
glm::ivec3 lightVolumeSize(glm::ivec3 volumeDims, int resolution);

class IsoRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::FirstHit; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
    ProfileModel profileModel() const override { return ProfileModel::Isosurface; }
    ProfileSettings profileSettings(const ParameterValues& values) const override;
    bool usesTransferFunction() const override { return false; }
};

class Tf2dRenderer final : public Renderer {
public:
    BrickCombine brickCombine(const ParameterValues&) const override { return BrickCombine::Over; }
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool needsTransferFunction2D() const override { return true; }
    bool usesTransferFunction() const override { return false; }
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
    ProfileModel profileModel() const override { return ProfileModel::Composite; }
    ProfileSettings profileSettings(const ParameterValues& values) const override {
        return compositingProfileSettings(values);
    }
};

// Object-order renderers: they draw proxy geometry (draw()) instead of
// casting rays.
class Texslice2dRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool objectOrder() const override { return true; }
    bool needsTransferFunction() const override { return true; }
    void draw(DrawContext& context, const ParameterValues& values) const override;
};

class Texslice3dRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool objectOrder() const override { return true; }
    bool needsTransferFunction() const override { return true; }
    void draw(DrawContext& context, const ParameterValues& values) const override;
};

// The isosurface as a triangle mesh, by marching cubes on the CPU
// (marching_cubes.h; the marching_cubes stage), drawn with a depth test.
// The mesh is kept while the volume, the isovalue and the stage's
// functions stay the same.
class MeshRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool objectOrder() const override { return true; }
    bool usesTransferFunction() const override { return false; }
    void draw(DrawContext& context, const ParameterValues& values) const override;

private:
    struct Cached;
    std::shared_ptr<const Cached> meshFor(const Volume& volume, double isovalue) const;
    mutable std::shared_ptr<const Cached> cached_;
    mutable std::mutex mutex_;
};

// Splatting (splatting.h): every voxel the transfer function shows, drawn as
// a Gaussian footprint (a point sprite), back to front in the splat stage's
// order. The points are kept while the volume, the transfer function and
// the walk stay the same.
class SplatRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool objectOrder() const override { return true; }
    bool needsTransferFunction() const override { return true; }
    std::string vertexShader() const override { return "renderers/splat.vert"; }
    void draw(DrawContext& context, const ParameterValues& values) const override;

private:
    struct Cached;
    std::shared_ptr<const Cached> pointsFor(const Volume& volume, const TransferFunction& tf, glm::dvec3 view) const;
    mutable std::shared_ptr<const Cached> cached_;
    mutable std::mutex mutex_;
};

// Shear-warp (shear_warp.h), orthographic views: the shearwarp stage's
// factorisation, one full-screen pass per slice into an intermediate image
// (two float targets taking turns), one warp pass onto the screen.
class ShearWarpRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    bool objectOrder() const override { return true; }
    bool needsTransferFunction() const override { return true; }
    std::string vertexShader() const override { return "voxlab/fullscreen.vert"; }
    void checkScene(const Scene& scene, const ParameterValues& values) const override;
    void draw(DrawContext& context, const ParameterValues& values) const override;
};

// Parameters several renderers declare alike (shared_parameters.cpp).
// Shading: shading, blinn, ka, kd, ks, shininess, light_azimuth,
// light_elevation, min_gradient, and the gradient's sobel and
// precomputed_gradients (see shaders/voxlab/lighting.glsl, gradients.glsl).
std::vector<ParameterSpec> shadingParameters(bool shadingByDefault);
// Compositing: early_termination, back_to_front, jitter (what the ray
// profile stops at, read from them, is declared at the top).
std::vector<ParameterSpec> compositingParameters();
// Draws the texture slicers' convex polygons in the order given (back to
// front), and, when `outline` is set, the outlines of every n-th polygon on
// top: n keeps about kOutlinedSlices outlines whatever the step, since at
// the default step (hundreds of polygons) outlining all of them paints a
// solid box and hides the structure the wireframe is there to show.
constexpr int kOutlinedSlices = 24;
void drawSlicePolygons(DrawContext& ctx, const std::vector<std::vector<glm::dvec3>>& polygons, bool outline);
int outlineStride(std::size_t polygons);  // n for that many polygons (>= 1)

}  // namespace voxlab
