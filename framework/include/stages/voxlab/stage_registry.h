// voxlab: what the stage folders bring, gathered (framework/stages/stage_registry.cpp).
//
// The module above the stages: each list is generated from the folders
// (framework/stages/stages.cmake), in the stages' teaching order. The
// modules below the stages never call these; a RenderEngine is handed its
// registry by whoever creates it (usually rendererRegistry() from here).
#pragma once
#include <string>

#include "voxlab/renderer.h"
#include "voxlab/renderers.h"

namespace voxlab {

// The built-in renderers: those each stage's renderer.cpp adds (VOXLAB_RENDERERS).
const RendererRegistry& rendererRegistry();

// Every stage's compositing components (component.cpp, VOXLAB_COMPOSITE_COMPONENTS).
const CompositeComponents& compositeComponents();

// The GLSL that calls every component at its phase (which the compositing
// stage's entry shader includes as its components.glsl): the components'
// files, their switches' uniforms, and components_classify(p, ray, out c),
// components_classified(c, p, ray), components_lit(c, p, ray).
std::string compositeComponentsGlsl();

}  // namespace voxlab
