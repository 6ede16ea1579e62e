// Tests for renderer parameters: every renderer declares well-formed
// parameters, and parameters in data units follow the volume's value range.
#include <gtest/gtest.h>

#include <set>

#include "support/error_of.h"
#include "voxlab/empty_space.h"
#include "voxlab/error.h"
#include "voxlab/renderers.h"
#include "voxlab/stage_registry.h"

namespace voxlab::testing {
namespace {

TEST(RendererParameters, EveryDeclarationIsWellFormed) {
    std::set<std::string> ids;
    for (const auto& r : rendererRegistry().all()) {
        SCOPED_TRACE(r->id());
        EXPECT_TRUE(ids.insert(r->id()).second) << "duplicate id";
        EXPECT_FALSE(r->description().empty());
        EXPECT_EQ(r->description().find('\n'), std::string::npos);
        std::set<std::string> names;
        for (const ParameterSpec& p : r->parameters()) {
            SCOPED_TRACE(p.name);
            EXPECT_TRUE(names.insert(p.name).second) << "declared twice";
            EXPECT_LE(p.minValue, p.defaultValue);
            EXPECT_LE(p.defaultValue, p.maxValue);
            EXPECT_FALSE(p.description.empty());
            if (p.type == ParameterType::Bool) EXPECT_TRUE(p.minValue == 0 && p.maxValue == 1);
        }
        // Defaults alone are always accepted.
        EXPECT_NO_THROW(r->resolveParameters({}, glm::dvec2(0.0, 1.0)));
    }
    for (const char* id : {"slicer", "mip", "minip", "average", "firsthit", "slab_mip", "composite", "iso", "tf2d"})
        EXPECT_TRUE(ids.count(id)) << id << " is not registered";
}

// The features compositing switches on come from their stages' folders:
// each component's parameters are composite's, its first switches it on
// (a Bool, off by default, so a scene that names none renders plain
// compositing), and its switch alone decides when its rules apply.
TEST(RendererParameters, CompositeComponentsBringTheirParameters) {
    const Renderer& composite = rendererRegistry().get("composite");
    std::set<std::string> declared;
    for (const ParameterSpec& p : composite.parameters()) declared.insert(p.name);
    std::set<std::string> switches;
    for (const auto& component : compositeComponents().all()) {
        const std::vector<ParameterSpec> params = component->parameters();
        ASSERT_FALSE(params.empty());
        SCOPED_TRACE(params.front().name);
        EXPECT_EQ(params.front().type, ParameterType::Bool);
        EXPECT_EQ(params.front().defaultValue, 0.0);
        switches.insert(params.front().name);
        for (const ParameterSpec& p : params) EXPECT_TRUE(declared.count(p.name)) << p.name;
        ParameterValues values = composite.resolveParameters({}, glm::dvec2(0.0, 1.0));
        EXPECT_FALSE(component->on(values));
        values[params.front().name] = 1.0;
        EXPECT_TRUE(component->on(values));
        // Switched on, a component that reads beyond a brick refuses bricks.
        if (component->readsBeyondBrick())
            EXPECT_NE(errorOf([&] { composite.brickCombine(values); }).find("reads beyond one brick"),
                      std::string::npos);
        else
            EXPECT_NO_THROW(composite.brickCombine(values));
        const bool skips = composite.emptySpaceRule(values).kind != EmptySpaceRule::Kind::None;
        EXPECT_EQ(skips, component->keepsSkipping());
    }
    EXPECT_EQ(switches, (std::set<std::string>{"gradient_opacity", "ambient_occlusion", "preintegrated", "shadows"}));
}

TEST(RendererParameters, DataUnitParametersFollowTheValueRange) {
    const Renderer& iso = rendererRegistry().get("iso");
    // Declared as fractions of the range: the default isovalue is mid-range.
    const ParameterValues ct = iso.resolveParameters({}, glm::dvec2(-1000.0, 3000.0));
    EXPECT_DOUBLE_EQ(ct.at("isovalue"), 1000.0);
    const ParameterValues u8 = iso.resolveParameters({}, glm::dvec2(0.0, 255.0));
    EXPECT_DOUBLE_EQ(u8.at("isovalue"), 127.5);
    // Given values are data units, checked against the range.
    EXPECT_DOUBLE_EQ(iso.resolveParameters({{"isovalue", 2500}}, glm::dvec2(-1000.0, 3000.0)).at("isovalue"), 2500);
    const std::string msg = errorOf([&] { iso.resolveParameters({{"isovalue", 300}}, glm::dvec2(0.0, 255.0)); });
    EXPECT_NE(msg.find("iso: parameter 'isovalue' = 300 is outside [0, 255]"), std::string::npos) << msg;
    // Without a range only names and types are checked.
    EXPECT_NO_THROW(iso.resolveParameters({{"isovalue", 1e6}}));
    EXPECT_THROW(iso.resolveParameters({{"refinement_steps", 1.5}}), Error);
    // parametersFor() is what panels show.
    for (const ParameterSpec& p : iso.parametersFor(glm::dvec2(10.0, 20.0)))
        if (p.name == "isovalue") {
            EXPECT_DOUBLE_EQ(p.minValue, 10.0);
            EXPECT_DOUBLE_EQ(p.maxValue, 20.0);
            EXPECT_DOUBLE_EQ(p.defaultValue, 15.0);
        }
}

TEST(RendererParameters, ShadingRenderersAskForTheGradientVolumeTheyUse) {
    const Renderer& composite = rendererRegistry().get("composite");
    EXPECT_FALSE(composite.precomputedGradients(composite.resolveParameters({})));
    EXPECT_EQ(composite.precomputedGradients(composite.resolveParameters({{"precomputed_gradients", 1}})),
              GradientEstimator::Central);
    EXPECT_EQ(composite.precomputedGradients(
                  composite.resolveParameters({{"precomputed_gradients", 1}, {"sobel", 1}})),
              GradientEstimator::Sobel);
    EXPECT_TRUE(composite.needsTransferFunction());
    EXPECT_FALSE(rendererRegistry().get("mip").needsTransferFunction());
    EXPECT_TRUE(rendererRegistry().get("tf2d").needsTransferFunction2D());
}

}  // namespace
}  // namespace voxlab::testing
