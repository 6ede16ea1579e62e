// The starter code (assignments/, generated from reference/ by
// tools/make_assignments.py): every stage is a loud stub. Rendering with it
// shows the not-implemented checkerboard wherever a stub ran, never a
// plausible dark image; the slicer, a worked example, works as given.
#include <gtest/gtest.h>

#include "support/gl_fixture.h"
#include "voxlab/error.h"
#include "voxlab/stage_registry.h"

namespace voxlab::testing {
namespace {

const std::string kAssignments = std::string(VOXLAB_SOURCE_DIR) + "/assignments";

// Fraction of pixels that are exactly the checkerboard's magenta.
double magentaFraction(const Image& img) {
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec4 c = img.at(x, y);
            n += c.r == 1.0f && c.g == 0.0f && c.b == 1.0f;
        }
    return double(n) / (double(img.width) * img.height);
}

TEST(Assignments, EveryRayCasterShowsTheNotImplementedPattern) {
    auto context = createHeadlessContext();
    RenderEngine engine(rendererRegistry(), kAssignments);
    const Volume v = makePhantom("phantom:sphere:32");
    engine.setVolume(v);
    for (const auto& r : rendererRegistry().all()) {
        if (r->id() == "slicer") continue;  // the worked example
        SCOPED_TRACE(r->id());
        Scene scene;
        scene.renderer = r->id();
        scene.camera.view = "+z";
        scene.camera.projection = Projection::Orthographic;
        scene.width = scene.height = 32;
        scene.interpolation = Interpolation::Trilinear;  // the sampling stage is a stub too
        Image img;
        try {
            img = engine.render(scene);
        } catch (const NotImplemented& e) {  // a C++ stage (texslice3d's proxy geometry)
            EXPECT_NE(std::string(e.what()).find("is not yet implemented"), std::string::npos);
            continue;
        }
        // Half the squares are magenta wherever the volume is drawn: the
        // whole box for a ray caster (0.5 of this image), only the
        // sphere's disc for a surface mesh (0.38 of it).
        EXPECT_GT(magentaFraction(img), 0.15) << r->id() << " does not show the pattern";
    }
}

TEST(Assignments, TheWorkedExampleRunsAsGiven) {
    auto context = createHeadlessContext();
    RenderEngine student(rendererRegistry(), kAssignments), reference(rendererRegistry());
    const Volume v = makePhantom("phantom:shells:32");
    Scene scene;
    scene.renderer = "slicer";
    scene.camera.view = "+x";
    scene.width = scene.height = 32;
    scene.interpolation = Interpolation::Hardware;  // not the (stubbed) sampling stage
    student.setVolume(v);
    reference.setVolume(v);
    const Image a = student.render(scene), b = reference.render(scene);
    EXPECT_EQ(magentaFraction(a), 0.0);
    EXPECT_EQ(a.rgba, b.rgba);
}

TEST(Assignments, TheReferenceNeverShowsThePattern) {
    auto context = createHeadlessContext();
    RenderEngine engine(rendererRegistry());
    const Volume v = makePhantom("phantom:sphere:32");
    engine.setVolume(v);
    for (const auto& r : rendererRegistry().all()) {
        Scene scene;
        scene.renderer = r->id();
        scene.width = scene.height = 32;
        try {
            r->checkScene(scene, {});
        } catch (const Error&) {  // shear-warp: orthographic views only
            scene.camera.projection = Projection::Orthographic;
        }
        EXPECT_EQ(magentaFraction(engine.render(scene)), 0.0) << r->id();
    }
}

}  // namespace
}  // namespace voxlab::testing
