// voxlab: the ray-profile panel (Dear ImGui), drawn into the current window.
//
// Plots a RayProfile against depth t: the sampled value (scaled to
// `valueRange`, usually the grey window), with the running maximum and the
// threshold/isovalue; the opacity of each sample and the accumulated opacity;
// and the accumulated colour as a colour strip under them. The stopping
// point is a vertical line and its reason is written under the plots;
// hovering shows the nearest sample's numbers.
#pragma once

#include <glm/glm.hpp>

#include "voxlab/ray_profile.h"

namespace voxlab {

// `label` is the widget's ID ("##profile" to show no text). Uses the space
// left in the current window (at least a small minimum).
void RayProfilePanel(const char* label, const RayProfile& profile, const glm::dvec2& valueRange);

}  // namespace voxlab
