// voxlab: the built-in renderers, in teaching order. Each stage's
// framework/stages/<stage>/renderer.cpp adds its own (VOXLAB_RENDERERS); the
// list of those stages is generated from framework/stages/stages.cmake, in
// its order. Nothing registers itself behind the linker's back.
#include "voxlab/renderer.h"

#define VOXLAB_STAGE_RENDERERS(stage) void stageRenderers_##stage(RendererRegistry& registry);
namespace voxlab {
#include "voxlab_stage_renderers.inc"
}  // namespace voxlab
#undef VOXLAB_STAGE_RENDERERS

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

}  // namespace voxlab
