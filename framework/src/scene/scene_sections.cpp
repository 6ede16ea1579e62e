// voxlab: the scene sections stages bring (voxlab/scene_section.h), gathered
// in the stages' order from the list framework/stages/stages.cmake
// generates. Nothing registers itself behind the linker's back.
#include "voxlab/scene_section.h"

#define VOXLAB_STAGE_SECTIONS(stage) void stageSceneSections_##stage(std::vector<SceneSection>& sections);
namespace voxlab {
#include "voxlab_stage_sections.inc"
}  // namespace voxlab
#undef VOXLAB_STAGE_SECTIONS

namespace voxlab {

const std::vector<SceneSection>& stageSceneSections() {
    static const std::vector<SceneSection> sections = [] {
        std::vector<SceneSection> s;
#define VOXLAB_STAGE_SECTIONS(stage) stageSceneSections_##stage(s);
#include "voxlab_stage_sections.inc"
#undef VOXLAB_STAGE_SECTIONS
        return s;
    }();
    return sections;
}

}  // namespace voxlab
