// Tests for the scene sections that crop and split the view and for the 2D
// transfer function: "roi", "cutting_plane", "tf2d". Each parses, survives
// the trip through toJson, and reports errors naming the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>

#include "support/error_of.h"
#include "voxlab/error.h"
#include "voxlab/project_root.h"
#include "voxlab/scene.h"
#include "voxlab/scene_section.h"

namespace voxlab::testing {
namespace {

using json = nlohmann::json;

Scene parse(const std::string& text) { return Scene::fromJson(json::parse(text), "scene.json", ""); }

std::string parseError(const std::string& text) {
    return errorOf([&] { parse(text); });
}

const char* kFull = R"({"dataset": "phantom:sphere:16", "renderer": "composite",
    "roi": {"min": [1, 2, 3], "max": [10, 11, 12.5]},
    "cutting_plane": {"point": [8, 8, 4], "normal": [0, 1, 1],
                      "other_side": {"renderer": "mip", "parameters": {"x": 2},
                                     "transfer_function": [{"value": 0, "color": [1, 0, 0], "alpha": 0.5}]}},
    "tf2d": {"widgets": [
        {"type": "triangle", "value": 0.5, "radius": 2, "alpha": 0.25, "color": [1, 0.5, 0]},
        {"type": "box", "value": [0.1, 0.9], "gradient": [0, 3], "alpha": 1, "color": [0, 0, 1]}]}})";

TEST(SceneSections, ParseEverySection) {
    const Scene s = parse(kFull);
    ASSERT_TRUE(s.roi);
    EXPECT_EQ(s.roi->min, glm::dvec3(1, 2, 3));
    EXPECT_EQ(s.roi->max, glm::dvec3(10, 11, 12.5));
    ASSERT_TRUE(s.cuttingPlane);
    EXPECT_EQ(*s.cuttingPlane->point, glm::dvec3(8, 8, 4));
    EXPECT_EQ(s.cuttingPlane->normal, glm::dvec3(0, 1, 1));
    EXPECT_EQ(s.cuttingPlane->otherRenderer, "mip");
    EXPECT_EQ(s.cuttingPlane->otherParameters.at("x"), 2.0);
    ASSERT_TRUE(s.cuttingPlane->otherTransferFunction);
    EXPECT_EQ(s.cuttingPlane->otherTransferFunction->points().size(), 1u);
    ASSERT_TRUE(s.transferFunction2D);
    const auto& w = s.transferFunction2D->widgets();
    ASSERT_EQ(w.size(), 2u);
    EXPECT_EQ(w[0].kind, Tf2dWidget::Kind::Triangle);
    EXPECT_EQ(w[0].valueRange.x, 0.5);
    EXPECT_EQ(w[0].radius, 2.0);
    EXPECT_EQ(w[1].kind, Tf2dWidget::Kind::Box);
    EXPECT_EQ(w[1].gradientRange, glm::dvec2(0, 3));
    EXPECT_EQ(w[1].color, glm::vec3(0, 0, 1));
}

TEST(SceneSections, DefaultsAndRoundTrip) {
    const Scene plain = parse(R"({"dataset": "phantom:sphere:16", "cutting_plane": {"normal": [0, 0, -1]}})");
    ASSERT_TRUE(plain.cuttingPlane);
    EXPECT_FALSE(plain.cuttingPlane->point);  // the centre, chosen when the volume is known
    EXPECT_EQ(plain.cuttingPlane->otherRenderer, "none");
    EXPECT_FALSE(plain.roi);
    EXPECT_FALSE(plain.transferFunction2D);

    for (const Scene& s : {parse(kFull), plain}) {
        const json out = s.toJson();
        const Scene back = Scene::fromJson(json::parse(out.dump()), "again.json", "");
        EXPECT_EQ(back.toJson(), out);
        EXPECT_EQ(back.transferFunction2D.has_value(), s.transferFunction2D.has_value());
        if (s.transferFunction2D) EXPECT_EQ(back.transferFunction2D->widgets(), s.transferFunction2D->widgets());
    }
}

TEST(SceneSections, ErrorsNameTheKey) {
    const std::string head = R"({"dataset": "phantom:a", )";
    const std::pair<const char*, const char*> cases[] = {
        {R"("roi": [1, 2])", "scene.json: roi: expected an object"},
        {R"("roi": {"min": [0, 0, 0]})", "scene.json: roi: needs both"},
        {R"("roi": {"min": [0, 0, 0], "max": [4, 4]})", "scene.json: roi.max: expected [x, y, z]"},
        {R"("roi": {"min": [0, 5, 0], "max": [4, 4, 4]})", "scene.json: roi: max must be greater"},
        {R"("roi": {"min": [0, 0, 0], "max": [4, 4, 4], "maxx": 1})", "scene.json: roi.maxx: unknown key"},
        {R"("cutting_plane": {"normal": [0, 0, 0]})", "scene.json: cutting_plane.normal: must not be zero"},
        {R"("cutting_plane": {"normal": [0, 0, "z"]})", "scene.json: cutting_plane.normal[2]: expected a number"},
        {R"("cutting_plane": {"other_side": {"renderer": 3}})",
         "scene.json: cutting_plane.other_side.renderer: expected a string"},
        {R"("cutting_plane": {"other_side": {"params": {}}})",
         "scene.json: cutting_plane.other_side.params: unknown key"},
        {R"("cutting_plane": {"other_side": {"parameters": {"a": "b"}}})",
         "scene.json: cutting_plane.other_side.parameters.a: expected a number"},
        {R"("tf2d": [])", "scene.json: tf2d: expected an object"},
        {R"("tf2d": {"widgets": [{"type": "circle"}]})", "scene.json: tf2d.widgets[0].type: unknown widget type"},
        {R"("tf2d": {"widgets": [{"type": "triangle", "value": 1, "radius": 0, "alpha": 1, "color": [1, 1, 1]}]})",
         "scene.json: tf2d.widgets[0].radius: expected a number > 0"},
        {R"("tf2d": {"widgets": [{"type": "box", "value": [2, 1], "gradient": [0, 1], "alpha": 1,
                                  "color": [1, 1, 1]}]})",
         "scene.json: tf2d.widgets[0].value: expected [lo, hi] with hi >= lo"},
        {R"("tf2d": {"widgets": [{"type": "box", "value": [0, 1], "gradient": [0, 1], "alpha": 2,
                                  "color": [1, 1, 1]}]})",
         "scene.json: tf2d.widgets[0].alpha: expected a number in 0..1"},
        {R"("tf2d": {"widgets": [{"type": "box", "value": [0, 1], "alpha": 1, "color": [1, 1, 1]}]})",
         "scene.json: tf2d.widgets[0]: missing key 'gradient'"},
        {R"("tf2d": {"widgets": [{"type": "triangle", "value": 1, "radius": 1, "alpha": 1, "color": [1, 1, 1],
                                  "gradient": [0, 1]}]})",
         "scene.json: tf2d.widgets[0].gradient: unknown key for a triangle widget"},
    };
    for (const auto& [body, want] : cases) {
        const std::string msg = parseError(head + body + "}");
        EXPECT_NE(msg.find(want), std::string::npos) << body << "\n  gave: " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

TEST(SceneSections, TooManyWidgetsAreRefused) {
    json widgets = json::array();
    for (int i = 0; i <= kMaxTf2dWidgets; ++i)
        widgets.push_back({{"type", "triangle"}, {"value", i}, {"radius", 1}, {"alpha", 1}, {"color", {1, 1, 1}}});
    const json scene = {{"dataset", "phantom:a"}, {"tf2d", {{"widgets", widgets}}}};
    const std::string msg = errorOf([&] { Scene::fromJson(scene, "scene.json", ""); });
    EXPECT_NE(msg.find("at most 16"), std::string::npos) << msg;
}

// The sections are the stages': each stage folder with a section.cpp (the
// oracle: the folders themselves) brings at least one, every section owns a
// key no other section and no key of the scene's own owns, its documentation
// is written as a scene writes it, and a scene without it writes nothing of it.
TEST(SceneSections, TheStagesSectionsAreFoundDocumentedAndWrittenOnlyWhenThere) {
    std::size_t folders = 0;
    for (const auto& entry : std::filesystem::directory_iterator(stagesRoot()))
        folders += std::filesystem::is_regular_file(entry.path() / "section.cpp");
    const std::vector<SceneSection>& sections = stageSceneSections();
    EXPECT_GE(folders, 2u);  // the cutting plane's and the 2D transfer function's, at least
    EXPECT_GE(sections.size(), folders);
    const json plain = parse(R"({"dataset": "phantom:sphere:16"})").toJson();
    std::set<std::string> keys;
    for (const SceneSection& section : sections) {
        const std::string key = section.key;
        EXPECT_TRUE(keys.insert(key).second) << key << " is owned twice";
        EXPECT_FALSE(plain.contains(key)) << key << " is written by a scene without it";
        EXPECT_EQ(std::string(section.doc).rfind("\"" + key + "\": ", 0), 0u) << section.doc;
    }
    for (const char* own : {"dataset", "renderer", "camera", "sampling", "parameters", "transfer_function", "roi"})
        EXPECT_FALSE(keys.count(own)) << own;
}

}  // namespace
}  // namespace voxlab::testing
