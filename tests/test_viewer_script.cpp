// Viewer scripts: every command parses, comments and blank lines are
// skipped, quoting works, and every error is one line naming FILE:LINE.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "support/error_of.h"
#include "support/temp_dir.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/viewer_script.h"

namespace voxlab::testing {
namespace {

std::vector<ViewerStep> parse(const std::string& text) { return parseViewerScriptText(text, "demo.vs"); }

std::string errorIn(const std::string& text) {
    return errorOf([&] { parse(text); });
}

// The example from the format's documentation, one of each command.
const char* kEveryCommand = R"(# a comment on its own line
load bonsai.nrrd              # a dataset
scene datasets/scenes/default.json

renderer composite
param early_termination 0.95
param shading true
step 0.5
interpolation trilinear
tf tf/bonsai.json
tf none
camera azimuth 40 elevation 25
camera pan 0.1 -0.2 zoom 2 view +x projection perspective distance 3 fov 35
rotate 30 10
window 0 255
split on
split off
split difference
implementation assignments
implementation reference
panel slices on
panel help off
click 320 240
size 1280 800
wait 3
screenshot out/viewer.png
quit
)";

TEST(ViewerScript, EveryCommandParses) {
    const std::vector<ViewerStep> steps = parse(kEveryCommand);
    struct Expected { const char* command; std::vector<std::string> args; int line; };
    const Expected expected[] = {
        {"load", {"bonsai.nrrd"}, 2},
        {"scene", {"datasets/scenes/default.json"}, 3},
        {"renderer", {"composite"}, 5},
        {"param", {"early_termination", "0.95"}, 6},
        {"param", {"shading", "true"}, 7},
        {"step", {"0.5"}, 8},
        {"interpolation", {"trilinear"}, 9},
        {"tf", {"tf/bonsai.json"}, 10},
        {"tf", {"none"}, 11},
        {"camera", {"azimuth", "40", "elevation", "25"}, 12},
        {"camera", {"pan", "0.1", "-0.2", "zoom", "2", "view", "+x", "projection", "perspective", "distance", "3",
                    "fov", "35"}, 13},
        {"rotate", {"30", "10"}, 14},
        {"window", {"0", "255"}, 15},
        {"split", {"on"}, 16},
        {"split", {"off"}, 17},
        {"split", {"difference"}, 18},
        {"implementation", {"assignments"}, 19},
        {"implementation", {"reference"}, 20},
        {"panel", {"slices", "on"}, 21},
        {"panel", {"help", "off"}, 22},
        {"click", {"320", "240"}, 23},
        {"size", {"1280", "800"}, 24},
        {"wait", {"3"}, 25},
        {"screenshot", {"out/viewer.png"}, 26},
        {"quit", {}, 27},
    };
    ASSERT_EQ(steps.size(), std::size(expected));
    for (size_t i = 0; i < steps.size(); ++i) {
        SCOPED_TRACE(expected[i].command);
        EXPECT_EQ(steps[i].command, expected[i].command);
        EXPECT_EQ(steps[i].args, expected[i].args);
        EXPECT_EQ(steps[i].line, expected[i].line);
        EXPECT_EQ(steps[i].file, "demo.vs");
    }
}

TEST(ViewerScript, CommentsBlankLinesAndQuotes) {
    const std::vector<ViewerStep> steps = parse(
        "\n   \n\t# only a comment\n"
        "  wait   2   # trailing comment\r\n"        // CRLF and extra blanks
        "load \"my data/a # b.nrrd\"  # quoted\n"  // blanks and '#' inside quotes
        "screenshot out/x.png#comment right after\n"
        "quit");                                     // no final newline
    ASSERT_EQ(steps.size(), 4u);
    EXPECT_EQ(steps[0].command, "wait");
    EXPECT_EQ(steps[0].args, std::vector<std::string>{"2"});
    EXPECT_EQ(steps[0].line, 4);
    EXPECT_EQ(steps[1].args, std::vector<std::string>{"my data/a # b.nrrd"});
    EXPECT_EQ(steps[2].args, std::vector<std::string>{"out/x.png"});
    EXPECT_EQ(steps[3].command, "quit");
    EXPECT_EQ(steps[3].line, 7);
    EXPECT_TRUE(parse("").empty());
    EXPECT_TRUE(parse("# nothing\n\n").empty());
}

TEST(ViewerScript, ErrorsNameFileAndLine) {
    const std::pair<const char*, const char*> cases[] = {
        {"quit\nrotat 30 10", "demo.vs:2: unknown command 'rotat'"},
        {"rotate 30", "demo.vs:1: rotate: expected 2 numbers"},
        {"rotate 30 10 5", "demo.vs:1: rotate: expected 2 numbers"},
        {"\nrotate 30 ten", "demo.vs:2: rotate: expected 2 numbers, got 'ten'"},
        {"rotate 30 nan", "demo.vs:1: rotate: expected 2 numbers, got 'nan'"},
        {"rotate 30 1e999", "demo.vs:1: rotate: expected 2 numbers, got '1e999'"},
        {"rotate 30 +-1", "demo.vs:1: rotate: expected 2 numbers, got '+-1'"},
        {"click 1 2px", "demo.vs:1: click: expected 2 numbers, got '2px'"},
        {"load", "demo.vs:1: load: expected 1 path"},
        {"load a b", "demo.vs:1: load: expected 1 path"},
        {"scene", "demo.vs:1: scene: expected 1 path"},
        {"renderer", "demo.vs:1: renderer: expected 1 renderer name"},
        {"param x", "demo.vs:1: param: expected a name and a number (or true/false)"},
        {"param x yes", "demo.vs:1: param: expected a name and a number (or true/false), got 'yes'"},
        {"step 0", "demo.vs:1: step: expected 1 number > 0, got '0'"},
        {"step", "demo.vs:1: step: expected 1 number > 0"},
        {"interpolation linear", "demo.vs:1: interpolation: expected nearest, trilinear, hardware, bspline or catmull-rom, got 'linear'"},
        {"tf", "demo.vs:1: tf: expected 1 path or 'none'"},
        {"camera", "demo.vs:1: camera: expected settings, e.g. 'camera azimuth 40 elevation 25'"},
        {"camera azimut 4",
         "demo.vs:1: camera: unknown setting 'azimut' (expected azimuth, elevation, distance, fov, zoom, pan, view "
         "or projection)"},
        {"camera azimuth", "demo.vs:1: camera: azimuth: expected a number"},
        {"camera azimuth x", "demo.vs:1: camera: azimuth: expected a number, got 'x'"},
        {"camera elevation 3 view", "demo.vs:1: camera: view: expected a value"},
        {"camera pan 1", "demo.vs:1: camera: pan: expected 2 numbers"},
        {"camera pan 1 y", "demo.vs:1: camera: pan: expected 2 numbers, got 'y'"},
        {"camera view +w", "demo.vs:1: camera: view: expected +x, -x, +y, -y, +z or -z, got '+w'"},
        {"camera projection fisheye", "demo.vs:1: camera: projection: expected perspective or orthographic, got "
                                      "'fisheye'"},
        {"camera zoom 0", "demo.vs:1: camera: zoom: expected a number > 0, got '0'"},
        {"camera distance -1", "demo.vs:1: camera: distance: expected a number > 0, got '-1'"},
        {"camera fov 180", "demo.vs:1: camera: fov: expected degrees in (0, 180), got '180'"},
        {"window 5 5", "demo.vs:1: window: expected 2 numbers LO HI with HI > LO"},
        {"window 0", "demo.vs:1: window: expected 2 numbers LO HI with HI > LO"},
        {"split maybe", "demo.vs:1: split: expected on, off or difference, got 'maybe'"},
        {"implementation", "demo.vs:1: implementation: expected a folder or 'reference'"},
        {"panel sidebar on", "demo.vs:1: panel: expected a panel (slices, tf, tf2d, profile, help or controls) and "
                             "on or off, got 'sidebar'"},
        {"panel tf maybe", "demo.vs:1: panel: expected a panel (slices, tf, tf2d, profile, help or controls) and "
                           "on or off, got 'maybe'"},
        {"divider 1.5", "demo.vs:1: divider: expected 1 number in (0, 1): the divider's place across the window, "
                        "got '1.5'"},
        {"right", "demo.vs:1: right: expected a renderer name or 'same'"},
        {"size 640", "demo.vs:1: size: expected 2 integers > 0"},
        {"size 640 4.5", "demo.vs:1: size: expected 2 integers > 0, got '4.5'"},
        {"size 0 480", "demo.vs:1: size: expected 2 integers > 0, got '0'"},
        {"wait -1", "demo.vs:1: wait: expected 1 integer >= 0 (frames), got '-1'"},
        {"wait", "demo.vs:1: wait: expected 1 integer >= 0 (frames)"},
        {"screenshot", "demo.vs:1: screenshot: expected 1 output path"},
        {"quit now", "demo.vs:1: quit: expected no arguments"},
        {"load \"unterminated", "demo.vs:1: unterminated quote"},
    };
    for (const auto& [text, message] : cases) {
        SCOPED_TRACE(text);
        EXPECT_EQ(errorIn(text), message);
    }
}

class ViewerScriptFile : public ::testing::Test {
protected:
    std::string write(const std::string& name, const std::string& text) {
        const std::string path = (dir / name).string();
        std::ofstream(path) << text;
        return path;
    }
    TempDir tmp_{"voxlab_viewer_script"};
    const std::filesystem::path dir = tmp_.path();
};

TEST_F(ViewerScriptFile, ReadsAFileAndNamesItInErrors) {
    const std::string good = write("good.vs", kEveryCommand);
    const std::vector<ViewerStep> steps = parseViewerScript(good);
    ASSERT_EQ(steps.size(), 25u);
    EXPECT_EQ(steps[0].file, good);
    EXPECT_EQ(stepLocation(steps[0]), good + ":2");

    const std::string bad = write("bad.vs", "wait 1\n\n# x\nsize 10\n");
    EXPECT_EQ(errorOf([&] { parseViewerScript(bad); }), bad + ":4: size: expected 2 integers > 0");
    const std::string missing = (dir / "missing.vs").string();
    EXPECT_EQ(errorOf([&] { parseViewerScript(missing); }), missing + ": cannot open viewer script");
}

// A data file is found next to the script, and a missing one is a located error.
TEST_F(ViewerScriptFile, DataPathsAreFoundNextToTheScript) {
    write("volume.nrrd", "x");
    const std::string script = write("s.vs", "load volume.nrrd\nload nowhere.nrrd\nload phantom:sphere:16\n");
    const std::vector<ViewerStep> steps = parseViewerScript(script);
    EXPECT_TRUE(std::filesystem::equivalent(dataPath(steps[0], 0), dir / "volume.nrrd"));
    const std::string error = errorOf([&] { dataPath(steps[1], 0); });
    EXPECT_EQ(error.rfind(script + ":2: load: nowhere.nrrd: no such file", 0), 0u) << error;
    EXPECT_EQ(dataPath(steps[2], 0), "phantom:sphere:16");
}

TEST(ViewerScript, TypedAccessors) {
    const std::vector<ViewerStep> steps = parse("param a -2.5e1\nparam b false\nsize 640 +480\npanel tf on\n"
                                                "panel tf off\nwindow 0 255");
    EXPECT_EQ(number(steps[0], 1), -25.0);
    EXPECT_EQ(number(steps[1], 1), 0.0);
    EXPECT_EQ(integer(steps[2], 0), 640);
    EXPECT_EQ(integer(steps[2], 1), 480);
    EXPECT_TRUE(onOff(steps[3], 1));
    EXPECT_FALSE(onOff(steps[4], 1));
    EXPECT_EQ(word(steps[3], 0), "tf");
    EXPECT_EQ(number(steps[5], 1), 255.0);
    // Wrong kind or index: a located error.
    EXPECT_EQ(errorOf([&] { number(steps[3], 0); }), "demo.vs:4: panel: expected a number, got 'tf'");
    EXPECT_EQ(errorOf([&] { integer(steps[0], 1); }), "demo.vs:1: param: expected an integer, got '-2.5e1'");
    EXPECT_EQ(errorOf([&] { onOff(steps[0], 0); }), "demo.vs:1: param: expected on or off, got 'a'");
    EXPECT_EQ(errorOf([&] { word(steps[2], 2); }), "demo.vs:3: size: missing argument 3");
    EXPECT_EQ(errorOf([&] { failStep(steps[5], "no volume loaded"); }), "demo.vs:6: window: no volume loaded");
}

TEST(ViewerScript, CameraStepsApplyInOrder) {
    const std::vector<ViewerStep> steps =
        parse("camera azimuth 40 elevation -25 pan 0.5 -0.25 zoom 2 distance 3 fov 45 projection orthographic\n"
              "camera view -x\n"
              "camera elevation 10\n"
              "window 0 1");
    CameraSpec camera;
    applyCameraStep(steps[0], &camera);
    EXPECT_EQ(camera.view, "");
    EXPECT_EQ(camera.azimuth, 40.0);
    EXPECT_EQ(camera.elevation, -25.0);
    EXPECT_EQ(camera.pan, glm::dvec2(0.5, -0.25));
    EXPECT_EQ(camera.zoom, 2.0);
    EXPECT_EQ(camera.distance, 3.0);
    EXPECT_EQ(camera.fov, 45.0);
    EXPECT_EQ(camera.projection, Projection::Orthographic);
    applyCameraStep(steps[1], &camera);
    EXPECT_EQ(camera.view, "-x");
    EXPECT_EQ(camera.zoom, 2.0);  // a view alone keeps zoom and pan
    EXPECT_EQ(camera.pan, glm::dvec2(0.5, -0.25));
    // An orbit setting leaves the axis view for its orbit angles (-x: azimuth -90).
    applyCameraStep(steps[2], &camera);
    EXPECT_EQ(camera.view, "");
    EXPECT_EQ(camera.azimuth, -90.0);
    EXPECT_EQ(camera.elevation, 10.0);
    EXPECT_EQ(errorOf([&] { applyCameraStep(steps[3], &camera); }), "demo.vs:4: window: not a camera step");
}

}  // namespace
}  // namespace voxlab::testing
