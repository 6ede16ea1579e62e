// voxlab: the built-in renderers. Each is declared here and defined in its
// own file under framework/src/renderers/; its GLSL entry point is
// shaders/renderers/ID.frag and its stage code is reference/ID/.
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

}  // namespace voxlab
