// Tests for scene files: a full scene, defaults, every error path, the round
// trip through toJson, transfer functions by path, and the data search path.
#include <gtest/gtest.h>

#include "support/error_of.h"
#include "support/temp_dir.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "voxlab/error.h"
#include "voxlab/scene.h"

using voxlab::Scene;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A fresh temporary folder, removed (with the environment variables the
// tests set) when the test ends.
class SceneTest : public ::testing::Test {
protected:
    void SetUp() override {
        ::unsetenv("VOXLAB_DATA_PATH");
        ::unsetenv("VOXLAB_ROOT");
    }
    void TearDown() override {
        ::unsetenv("VOXLAB_DATA_PATH");
        ::unsetenv("VOXLAB_ROOT");
    }
    std::string write(const std::string& rel, const std::string& text) {
        const fs::path p = dir / rel;
        fs::create_directories(p.parent_path());
        std::ofstream(p) << text;
        return p.string();
    }
    voxlab::testing::TempDir tmp_{"voxlab_scene"};
    const fs::path dir = tmp_.path();
};

Scene parse(const std::string& text, const std::string& baseDir = "") {
    return Scene::fromJson(json::parse(text), "scene.json", baseDir);
}

using voxlab::testing::errorOf;

const char* kPoints = R"([{"value": 40, "color": [1, 1, 1], "alpha": 0},
                          {"value": 200, "color": [1, 0.5, 0.25], "alpha": 0.75}])";

}  // namespace

TEST_F(SceneTest, ParsesAFullScene) {
    write("data/vol_full_test.nrrd", "x");
    const std::string path = write("data/scene.json", std::string(R"({
        "dataset": "vol_full_test.nrrd",
        "renderer": "dvr",
        "camera": {"azimuth": 45, "elevation": -10, "distance": 3, "fov": 40, "zoom": 1.5},
        "projection": "orthographic",
        "size": [320, 200],
        "sampling": {"step": 0.25, "interpolation": "nearest"},
        "window": [-100, 1500.5],
        "background": [0.1, 0.2, 0.3],
        "parameters": {"offset": 2.5, "shade": true, "flat": false},
        "transfer_function": )") + kPoints + "}");
    const Scene s = Scene::load(path);
    EXPECT_EQ(s.dataset, (dir / "data" / "vol_full_test.nrrd").string());
    EXPECT_EQ(s.renderer, "dvr");
    EXPECT_EQ(s.camera.view, "");
    EXPECT_EQ(s.camera.azimuth, 45);
    EXPECT_EQ(s.camera.elevation, -10);
    EXPECT_EQ(s.camera.distance, 3);
    EXPECT_EQ(s.camera.fov, 40);
    EXPECT_EQ(s.camera.zoom, 1.5);
    EXPECT_EQ(s.camera.projection, voxlab::Projection::Orthographic);
    EXPECT_EQ(s.width, 320);
    EXPECT_EQ(s.height, 200);
    EXPECT_EQ(s.step, 0.25);
    EXPECT_EQ(s.interpolation, voxlab::Interpolation::Nearest);
    ASSERT_TRUE(s.window.has_value());
    EXPECT_EQ(*s.window, glm::dvec2(-100, 1500.5));
    EXPECT_EQ(s.background, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(s.parameters, (voxlab::ParameterValues{{"offset", 2.5}, {"shade", 1.0}, {"flat", 0.0}}));
    ASSERT_TRUE(s.transferFunction.has_value());
    ASSERT_EQ(s.transferFunction->points().size(), 2u);
    EXPECT_EQ(s.transferFunction->points()[1].alpha, 0.75f);
}

TEST_F(SceneTest, Defaults) {
    const Scene s = parse(R"({"dataset": "phantom:sphere:64"})");
    EXPECT_EQ(s.dataset, "phantom:sphere:64");
    EXPECT_EQ(s.renderer, "mip");
    EXPECT_EQ(s.camera.view, "");
    EXPECT_EQ(s.camera.azimuth, voxlab::CameraSpec().azimuth);
    EXPECT_EQ(s.camera.projection, voxlab::Projection::Perspective);
    EXPECT_EQ(s.width, 256);
    EXPECT_EQ(s.height, 256);
    EXPECT_EQ(s.step, 0.5);
    EXPECT_EQ(s.interpolation, voxlab::Interpolation::Trilinear);
    EXPECT_FALSE(s.window.has_value());
    EXPECT_EQ(s.background, glm::vec3(0.0f));
    EXPECT_TRUE(s.parameters.empty());
    EXPECT_FALSE(s.transferFunction.has_value());
}

TEST_F(SceneTest, ProjectionDefaultsFollowTheCamera) {
    EXPECT_EQ(parse(R"({"dataset": "phantom:a", "camera": {"view": "-y"}})").camera.projection,
              voxlab::Projection::Orthographic);
    EXPECT_EQ(parse(R"({"dataset": "phantom:a", "camera": {"view": "+x"}, "projection": "perspective"})")
                  .camera.projection,
              voxlab::Projection::Perspective);
    EXPECT_EQ(parse(R"({"dataset": "phantom:a", "camera": {"azimuth": 10}})").camera.projection,
              voxlab::Projection::Perspective);
    const Scene zoomed = parse(R"({"dataset": "phantom:a", "camera": {"view": "+z", "zoom": 2}})");
    EXPECT_EQ(zoomed.camera.view, "+z");
    EXPECT_EQ(zoomed.camera.zoom, 2);
}

TEST_F(SceneTest, EveryErrorNamesTheKey) {
    struct Case {
        const char* body;  // inserted after "dataset": "phantom:a"
        const char* message;
    };
    const Case cases[] = {
        {R"("colour": 1)", "scene.json: colour: unknown key"},
        {R"("camera": {"azimut": 1})", "scene.json: camera.azimut: unknown key"},
        {R"("sampling": {"stepp": 1})", "scene.json: sampling.stepp: unknown key"},
        {R"("transfer_function": [{"value": 0, "color": [0,0,0], "alpha": 0, "opacity": 1}])",
         "scene.json: transfer_function[0]: unknown key 'opacity'"},
        {R"("transfer_function": {"points": [{"value": 0, "color": [0,0], "alpha": 0}]})",
         "scene.json: transfer_function.points[0].color: expected an array of 3 numbers"},
        {R"("transfer_function": 5)", "scene.json: transfer_function: expected an array"},
        {R"("renderer": 1)", "scene.json: renderer: expected a string"},
        {R"("renderer": "")", "scene.json: renderer: expected a renderer name"},
        {R"("camera": "front")", "scene.json: camera: expected an object"},
        {R"("camera": {"view": 3})", "scene.json: camera.view: expected a string"},
        {R"("camera": {"view": "+w"})", "scene.json: camera.view: unknown view '+w'"},
        {R"("camera": {"view": "+x", "azimuth": 3})", "scene.json: camera: 'view' cannot be combined with 'azimuth'"},
        {R"("camera": {"azimuth": "3"})", "scene.json: camera.azimuth: expected a number"},
        {R"("camera": {"elevation": true})", "scene.json: camera.elevation: expected a number"},
        {R"("camera": {"distance": -1})", "scene.json: camera.distance: expected a number > 0"},
        {R"("camera": {"fov": 180})", "scene.json: camera.fov: expected a number of degrees"},
        {R"("camera": {"zoom": 0})", "scene.json: camera.zoom: expected a number > 0"},
        {R"("projection": 1)", "scene.json: projection: expected a string"},
        {R"("projection": "fisheye")", "scene.json: projection: unknown projection 'fisheye'"},
        {R"("size": "256")", "scene.json: size: expected [width, height]"},
        {R"("size": [256])", "scene.json: size: expected [width, height]"},
        {R"("size": [0, 10])", "scene.json: size: expected [width, height]"},
        {R"("size": [10, 8193])", "scene.json: size: expected [width, height]"},
        {R"("size": [1.5, 2])", "scene.json: size: expected [width, height]"},
        {R"("sampling": 1)", "scene.json: sampling: expected an object"},
        {R"("sampling": {"step": "x"})", "scene.json: sampling.step: expected a number"},
        {R"("sampling": {"step": 0})", "scene.json: sampling.step: expected a number > 0 and <= 64"},
        {R"("sampling": {"step": 64.5})", "scene.json: sampling.step: expected a number > 0 and <= 64"},
        {R"("sampling": {"interpolation": 3})", "scene.json: sampling.interpolation: expected a string"},
        {R"("sampling": {"interpolation": "cubic"})",
         "scene.json: sampling.interpolation: unknown interpolation 'cubic'"},
        {R"("window": 5)", "scene.json: window: expected [lo, hi]"},
        {R"("window": [1])", "scene.json: window: expected [lo, hi]"},
        {R"("window": [10, 10])", "scene.json: window: expected [lo, hi], numbers with hi > lo"},
        {R"("window": [10, 5])", "scene.json: window: expected [lo, hi], numbers with hi > lo"},
        {R"("window": ["a", 1])", "scene.json: window[0]: expected a number"},
        {R"("background": "black")", "scene.json: background: expected [r, g, b]"},
        {R"("background": [1, 1])", "scene.json: background: expected [r, g, b]"},
        {R"("background": [2, 0, 0])", "scene.json: background: expected [r, g, b], numbers in 0..1"},
        {R"("parameters": 3)", "scene.json: parameters: expected an object"},
        {R"("parameters": {"a": "x"})", "scene.json: parameters.a: expected a number or true/false"},
        {R"("dataset": 1)", "scene.json: dataset: expected a string"},
    };
    for (const Case& c : cases) {
        // A repeated "dataset" key: nlohmann keeps the last one.
        const std::string text = std::string(R"({"dataset": "phantom:a", )") + c.body + "}";
        const std::string msg = errorOf([&] { parse(text); });
        EXPECT_EQ(msg.rfind(c.message, 0), 0u) << "got '" << msg << "' for " << c.body;
        EXPECT_EQ(msg.find('\n'), std::string::npos);
    }
    EXPECT_EQ(errorOf([] { parse("{}"); }), "scene.json: dataset: missing (required)");
    EXPECT_EQ(errorOf([] { parse("[1]"); }), "scene.json: expected a JSON object");
    EXPECT_EQ(errorOf([] { parse(R"({"dataset": "no_such_volume_xyz.nrrd"})"); })
                  .rfind("scene.json: dataset: no_such_volume_xyz.nrrd: no such file (searched: ", 0),
              0u);
}

TEST_F(SceneTest, LoadReportsFileErrorsOnOneLine) {
    const std::string missing = (dir / "none.json").string();
    EXPECT_EQ(errorOf([&] { Scene::load(missing); }).rfind(missing + ": cannot open", 0), 0u);
    const std::string bad = write("bad.json", "{\n  \"dataset\": \"phantom:a\",\n  \"size\": [1, 2,\n}\n");
    const std::string msg = errorOf([&] { Scene::load(bad); });
    EXPECT_EQ(msg.rfind(bad + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find("line 4"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST_F(SceneTest, TransferFunctionByPath) {
    write("scenes/my_tf_test.json", std::string(R"({"name": "t", "points": )") + kPoints + "}");
    write("scenes/broken_tf_test.json", R"([{"value": 1, "color": [1, 1, 1], "alpha": 7}])");
    const std::string base = (dir / "scenes").string();
    const Scene s = parse(R"({"dataset": "phantom:a", "transfer_function": "my_tf_test.json"})", base);
    ASSERT_TRUE(s.transferFunction.has_value());
    EXPECT_EQ(s.transferFunction->points().size(), 2u);
    EXPECT_EQ(s.transferFunction->points()[1].color.g, 0.5f);

    EXPECT_EQ(errorOf([&] { parse(R"({"dataset": "phantom:a", "transfer_function": "gone_tf.json"})", base); })
                  .rfind("scene.json: transfer_function: gone_tf.json: no such file", 0),
              0u);
    const std::string msg =
        errorOf([&] { parse(R"({"dataset": "phantom:a", "transfer_function": "broken_tf_test.json"})", base); });
    EXPECT_NE(msg.find("broken_tf_test.json: points[0].alpha"), std::string::npos) << msg;
}

// The bundled presets are found through the project's datasets/ folder.
TEST_F(SceneTest, PresetTransferFunctionsResolve) {
    const Scene s = parse(R"({"dataset": "phantom:a", "transfer_function": "tf/cthead.json"})");
    ASSERT_TRUE(s.transferFunction.has_value());
    EXPECT_GE(s.transferFunction->points().size(), 3u);
}

namespace {

void expectSameScene(const Scene& a, const Scene& b) {
    EXPECT_EQ(a.dataset, b.dataset);
    EXPECT_EQ(a.renderer, b.renderer);
    EXPECT_EQ(a.camera.view, b.camera.view);
    if (a.camera.view.empty()) {
        EXPECT_EQ(a.camera.azimuth, b.camera.azimuth);
        EXPECT_EQ(a.camera.elevation, b.camera.elevation);
        EXPECT_EQ(a.camera.distance, b.camera.distance);
        EXPECT_EQ(a.camera.fov, b.camera.fov);
    }
    EXPECT_EQ(a.camera.zoom, b.camera.zoom);
    EXPECT_EQ(a.camera.projection, b.camera.projection);
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.step, b.step);
    EXPECT_EQ(a.interpolation, b.interpolation);
    EXPECT_EQ(a.window, b.window);
    EXPECT_EQ(a.background, b.background);
    EXPECT_EQ(a.parameters, b.parameters);
    ASSERT_EQ(a.transferFunction.has_value(), b.transferFunction.has_value());
    if (!a.transferFunction) return;
    const auto &pa = a.transferFunction->points(), &pb = b.transferFunction->points();
    ASSERT_EQ(pa.size(), pb.size());
    for (size_t i = 0; i < pa.size(); ++i) {
        EXPECT_EQ(pa[i].value, pb[i].value);
        EXPECT_EQ(pa[i].color, pb[i].color);
        EXPECT_EQ(pa[i].alpha, pb[i].alpha);
    }
}

}  // namespace

TEST_F(SceneTest, RoundTrips) {
    const std::string texts[] = {
        std::string(R"({"dataset": "phantom:sphere:32", "renderer": "dvr",
            "camera": {"azimuth": 12.3, "elevation": 45.6, "distance": 3.3, "fov": 25, "zoom": 0.7},
            "size": [17, 9], "sampling": {"step": 0.1, "interpolation": "nearest"},
            "window": [-0.3, 7.1], "background": [0.1, 0.7, 1],
            "parameters": {"x": 0.1, "on": true}, "transfer_function": )") + kPoints + "}",
        R"({"dataset": "phantom:a", "camera": {"view": "-z", "zoom": 3}, "projection": "perspective"})",
        R"({"dataset": "phantom:a", "camera": {"view": "+y"}})",
        R"({"dataset": "phantom:a"})",
    };
    for (const std::string& text : texts) {
        const Scene s = parse(text);
        const json out = s.toJson();
        const Scene back = Scene::fromJson(json::parse(out.dump()), "again.json", "");
        SCOPED_TRACE(out.dump());
        expectSameScene(s, back);
    }
    // A resolved file path survives the trip too.
    write("rt_vol_test.nrrd", "x");
    const Scene withFile = parse(R"({"dataset": "rt_vol_test.nrrd"})", dir.string());
    expectSameScene(withFile, Scene::fromJson(withFile.toJson(), "again.json", ""));
}

TEST(Interpolation, NamesAndParsing) {
    EXPECT_STREQ(voxlab::interpolationName(voxlab::Interpolation::Nearest), "nearest");
    EXPECT_STREQ(voxlab::interpolationName(voxlab::Interpolation::Trilinear), "trilinear");
    EXPECT_EQ(voxlab::parseInterpolation("nearest"), voxlab::Interpolation::Nearest);
    EXPECT_EQ(voxlab::parseInterpolation("trilinear"), voxlab::Interpolation::Trilinear);
    EXPECT_THROW(voxlab::parseInterpolation("linear"), voxlab::Error);
}

TEST_F(SceneTest, ResolveDataPathSearchOrder) {
    const std::string name = "order_test.nrrd";
    const fs::path base = dir / "base", a = dir / "a", b = dir / "b", root = dir / "root";
    for (const fs::path& d : {base, a, b, root / "datasets"}) write((d / name).string(), "x");
    ::setenv("VOXLAB_DATA_PATH", (":" + a.string() + "::" + b.string()).c_str(), 1);
    ::setenv("VOXLAB_ROOT", root.string().c_str(), 1);

    EXPECT_EQ(voxlab::resolveDataPath("phantom:cube:8", base.string()), "phantom:cube:8");
    EXPECT_EQ(voxlab::resolveDataPath(name, base.string()), (base / name).string());
    fs::remove(base / name);
    EXPECT_EQ(voxlab::resolveDataPath(name, base.string()), (a / name).string());
    fs::remove(a / name);
    EXPECT_EQ(voxlab::resolveDataPath(name, base.string()), (b / name).string());
    fs::remove(b / name);
    EXPECT_EQ(voxlab::resolveDataPath(name, base.string()), (root / "datasets" / name).string());
    // An absolute path is taken as is.
    EXPECT_EQ(voxlab::resolveDataPath((root / "datasets" / name).string()), (root / "datasets" / name).string());
    fs::remove(root / "datasets" / name);

    const std::string msg = errorOf([&] { voxlab::resolveDataPath(name, base.string()); });
    const std::string searched = name + ", " + (base / name).string() + ", " + (a / name).string() + ", " +
                                 (b / name).string() + ", " + (root / "datasets" / name).string();
    EXPECT_EQ(msg, name + ": no such file (searched: " + searched + ")");

    // Relative to the working directory comes first of all.
    write((base / name).string(), "x");
    write(name, "x");
    const fs::path cwd = fs::current_path();
    fs::current_path(dir);
    const std::string found = voxlab::resolveDataPath(name, base.string());
    fs::current_path(cwd);
    EXPECT_EQ(found, name);
}

TEST_F(SceneTest, ProjectRoot) {
    EXPECT_EQ(voxlab::projectRoot(), VOXLAB_SOURCE_DIR);
    ::setenv("VOXLAB_ROOT", "/somewhere/else", 1);
    EXPECT_EQ(voxlab::projectRoot(), "/somewhere/else");
    // Without VOXLAB_ROOT the compiled-in datasets/ folder is searched last.
    ::unsetenv("VOXLAB_ROOT");
    const std::string msg = errorOf([] { voxlab::resolveDataPath("nothing_here_xyz.nrrd"); });
    EXPECT_NE(msg.find(std::string(VOXLAB_SOURCE_DIR) + "/datasets/nothing_here_xyz.nrrd)"), std::string::npos)
        << msg;
}
