// voxlab: the built-in renderers, in teaching order, and the compositing
// components. Each stage's framework/stages/<stage>/renderer.cpp adds its
// renderers (VOXLAB_RENDERERS), its component.cpp its component
// (VOXLAB_COMPOSITE_COMPONENTS); the lists of those stages are generated
// from framework/stages/stages.cmake, in its order. Nothing registers itself
// behind the linker's back.
#include "voxlab/renderer.h"
#include "voxlab/renderers.h"

#define VOXLAB_STAGE_RENDERERS(stage) void stageRenderers_##stage(RendererRegistry& registry);
namespace voxlab {
#include "voxlab_stage_renderers.inc"
}  // namespace voxlab
#undef VOXLAB_STAGE_RENDERERS
#define VOXLAB_STAGE_COMPONENTS(stage) void stageComponents_##stage(CompositeComponents& components);
namespace voxlab {
#include "voxlab_stage_components.inc"
}  // namespace voxlab
#undef VOXLAB_STAGE_COMPONENTS

namespace voxlab {

const RendererRegistry& rendererRegistry() {
    static const RendererRegistry registry = [] {
        RendererRegistry r;
#define VOXLAB_STAGE_RENDERERS(stage) stageRenderers_##stage(r);
#include "voxlab_stage_renderers.inc"
#undef VOXLAB_STAGE_RENDERERS
        return r;
    }();
    return registry;
}

const CompositeComponents& compositeComponents() {
    static const CompositeComponents components = [] {
        CompositeComponents c;
#define VOXLAB_STAGE_COMPONENTS(stage) stageComponents_##stage(c);
#include "voxlab_stage_components.inc"
#undef VOXLAB_STAGE_COMPONENTS
        return c;
    }();
    return components;
}

bool CompositeComponent::on(const ParameterValues& values) const {
    const auto it = values.find(parameters().front().name);
    return it != values.end() && it->second != 0.0;
}

}  // namespace voxlab
