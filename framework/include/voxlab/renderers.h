// voxlab: the built-in renderers. Each is declared here and defined in its
// own file under framework/src/renderers/ (ID_renderer.cpp); its GLSL entry
// point is shaders/renderers/ID.frag and its stage code is reference/ID/.
#pragma once

#include "voxlab/renderer.h"

namespace voxlab {

class SlicerRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
};

class MipRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
};

class MinipRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
};

class AverageRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
};

class FirstHitRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
};

class SlabMipRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
};

class CompositeRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool needsTransferFunction() const override { return true; }
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
};

class IsoRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
};

class Tf2dRenderer final : public Renderer {
public:
    std::string id() const override;
    std::string description() const override;
    std::vector<ParameterSpec> parameters() const override;
    bool needsTransferFunction2D() const override { return true; }
    EmptySpaceRule emptySpaceRule(const ParameterValues& values) const override;
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

// Parameters several renderers declare alike (shared_parameters.cpp).
// Shading: shading, blinn, ka, kd, ks, shininess, light_azimuth,
// light_elevation, min_gradient, and the gradient's sobel and
// precomputed_gradients (see shaders/voxlab/lighting.glsl, gradients.glsl).
std::vector<ParameterSpec> shadingParameters(bool shadingByDefault);
// Compositing: early_termination, back_to_front, jitter.
std::vector<ParameterSpec> compositingParameters();
// Draws the texture slicers' convex polygons in the order given (back to
// front), and their outlines on top when `outline` is set.
void drawSlicePolygons(DrawContext& ctx, const std::vector<std::vector<glm::dvec3>>& polygons, bool outline);

}  // namespace voxlab
