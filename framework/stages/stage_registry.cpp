// voxlab: the built-in renderers, in teaching order, and the compositing
// components (voxlab/stage_registry.h). Each stage's framework/stages/<stage>/renderer.cpp adds its
// renderers (VOXLAB_RENDERERS), its component.cpp its component
// (VOXLAB_COMPOSITE_COMPONENTS); the lists of those stages are generated
// from framework/stages/stages.cmake, in its order. Nothing registers itself
// behind the linker's back.
#include "voxlab/stage_registry.h"

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
#define VOXLAB_STAGE_COMPONENTS(stage) \
    c.setStage(#stage);                \
    stageComponents_##stage(c);
#include "voxlab_stage_components.inc"
#undef VOXLAB_STAGE_COMPONENTS
        return c;
    }();
    return components;
}

std::string compositeComponentsGlsl() {
    using Phase = CompositeComponent::Phase;
    const CompositeComponents& components = compositeComponents();
    std::string includes, uniforms, classify, classified, lit;
    for (std::size_t i = 0; i < components.all().size(); ++i) {
        const std::string stage = components.stage(i);
        const std::string on = "u_" + components.all()[i]->switchName();
        includes += "#include \"stages/" + stage + "/component.glsl\"\n";
        uniforms += "uniform int " + on + ";\n";
        const std::string call = stage + "_component(";
        switch (components.all()[i]->phase()) {
        case Phase::Classify:
            classify += "    if (" + on + " != 0) {\n        c = " + call + "vec4(0.0), p, ray);\n        return true;\n    }\n";
            break;
        case Phase::Classified: classified += "    if (" + on + " != 0) c = " + call + "c, p, ray);\n"; break;
        case Phase::Lit: lit += "    if (" + on + " != 0) c = " + call + "c, p, ray);\n"; break;
        }
    }
    return "// Generated (compositeComponentsGlsl, framework/stages/stage_registry.cpp): the\n"
           "// compositing components of framework/stages/*/component.glsl, each under its switch.\n"
           "#ifndef VOXLAB_COMPOSITE_COMPONENTS_GLSL\n#define VOXLAB_COMPOSITE_COMPONENTS_GLSL\n" +
           includes + uniforms +
           "bool components_classify(vec3 p, Ray ray, out vec4 c) {\n" + classify +
           "    c = vec4(0.0);\n    return false;\n}\n"
           "vec4 components_classified(vec4 c, vec3 p, Ray ray) {\n" + classified + "    return c;\n}\n"
           "vec4 components_lit(vec4 c, vec3 p, Ray ray) {\n" + lit + "    return c;\n}\n#endif\n";
}

}  // namespace voxlab
