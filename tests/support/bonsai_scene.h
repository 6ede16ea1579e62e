// Test support: bonsai at 96x96 from azimuth 35, elevation 25, step 0.5,
// the view the tests that hold an optimisation against the plain render
// (empty-space skipping, bricks) draw every renderer with.
#pragma once

#include <utility>
#include <vector>

#include "gl_fixture.h"
#include "voxlab/scene.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"

namespace voxlab::testing {

struct BonsaiView {
    const char* renderer;
    std::vector<std::pair<const char*, double>> parameters;
    Interpolation interpolation = Interpolation::Trilinear;
    bool transferFunction = false;    // datasets/tf/bonsai.json
    bool transferFunction2D = false;  // datasets/tf2d/bonsai.json
    Projection projection = Projection::Perspective;
};

inline Scene bonsaiScene(const BonsaiView& v) {
    Scene scene;
    scene.renderer = v.renderer;
    scene.camera.azimuth = 35.0;
    scene.camera.elevation = 25.0;
    scene.camera.projection = v.projection;
    scene.width = scene.height = 96;
    scene.step = 0.5;
    scene.interpolation = v.interpolation;
    for (const auto& [name, value] : v.parameters) scene.parameters[name] = value;
    if (v.transferFunction) scene.transferFunction = TransferFunction::load(datasetPath("tf/bonsai.json"));
    if (v.transferFunction2D) scene.transferFunction2D = TransferFunction2D::load(datasetPath("tf2d/bonsai.json"));
    return scene;
}

}  // namespace voxlab::testing
