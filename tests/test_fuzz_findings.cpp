// Inputs the fuzz targets (tests/fuzz/) found, kept as ordinary tests so that
// the build without clang checks them too. Each names its target and what was
// wrong before the fix.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "support/error_of.h"
#include "voxlab/scene.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"

using namespace voxlab;
using voxlab::testing::errorOf;
using json = nlohmann::json;

namespace {

std::string sceneError(const std::string& text) {
    return errorOf([&] { Scene::fromJson(json::parse(text), "scene.json", ""); });
}

}  // namespace

// fuzz_scene, fuzz_tf, fuzz_tf2d: keys and strings of a JSON document were
// echoed raw, so a "\n" in one split the error over two lines. Control
// characters are now written as JSON escapes, as they appear in the file.
TEST(FuzzFindings, SceneKeysWithControlCharactersStayOnOneLine) {
    EXPECT_EQ(sceneError(R"({"dataset": "phantom:sphere", "rende\nr": 1})"),
              "scene.json: rende\\nr: unknown key");
    EXPECT_EQ(sceneError(R"({"dataset": "phantom:sphere", "parameters": {"x\ty\r": "a"}})"),
              "scene.json: parameters.x\\ty\\r: expected a number or true/false");
    EXPECT_EQ(sceneError(R"({"dataset": "phantom:sphere", "camera": {"view": "+z\u001b[2J"}})"),
              "scene.json: camera.view: unknown view '+z\\u001b[2J' (expected +x -x +y -y +z -z)");
    const std::string missing = sceneError(R"({"dataset": "no\nsuch.nrrd"})");
    EXPECT_EQ(missing.rfind("scene.json: dataset: no\\nsuch.nrrd: no such file (searched: no\\nsuch.nrrd", 0), 0u)
        << missing;
    EXPECT_EQ(missing.find('\n'), std::string::npos) << missing;
}

TEST(FuzzFindings, TransferFunctionKeysWithControlCharactersStayOnOneLine) {
    EXPECT_EQ(errorOf([] {
                  TransferFunction::fromJson(
                      json::parse(R"([{"value": 1, "color": [1, 1, 1], "alpha": 1, "q\nz": 1}])"), "tf.json");
              }),
              "tf.json: points[0]: unknown key 'q\\nz'");
    EXPECT_EQ(errorOf([] { TransferFunction::fromJson(json::parse(R"({"\name": 1})"), "tf.json"); }),
              "tf.json: unknown key '\\name'");
    // Embedded in a scene, the scene's message is escaped once, not twice.
    EXPECT_EQ(sceneError(R"({"dataset": "phantom:sphere", "transfer_function": {"points": [], "a\nb": 1}})"),
              "scene.json: transfer_function: unknown key 'a\\nb'");
}

TEST(FuzzFindings, Tf2dStringsWithControlCharactersStayOnOneLine) {
    EXPECT_EQ(errorOf([] {
                  TransferFunction2D::fromJson(json::parse(R"({"widgets": [{"type": "trian\ne"}]})"), "tf2d.json");
              }),
              "tf2d.json: widgets[0].type: unknown widget type 'trian\\ne' (expected triangle or box)");
    EXPECT_EQ(errorOf([] { TransferFunction2D::fromJson(json::parse(R"({"widgets": [], "\u007f": 0})"), "t"); }),
              "t: \\u007f: unknown key");
}
