// The viewer as a user drives it: a viewer script (voxlab view --script)
// run in a real window under Xvfb loads a dataset, switches technique,
// opens the split view with the student's starter code against the
// reference, the difference heat map, the slice and ray-profile panels, and
// saves screenshots, which are then checked: the expected size, not blank,
// the panels present, the student side showing its "not implemented"
// checkerboard and the reference side not.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/run_command.h"
#include "voxlab/image.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

struct Region {
    int x0, y0, x1, y1;
};

// Mean and spread of the grey level over a region.
struct Stats {
    double mean = 0, spread = 0, magenta = 0;  // magenta: share of the stub's magenta pixels
};

Stats stats(const Image& img, Region r) {
    double sum = 0, sum2 = 0, magenta = 0;
    int n = 0;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const glm::vec4 c = img.at(x, y);
            const double g = (c.r + c.g + c.b) / 3.0;
            sum += g, sum2 += g * g, ++n;
            if (c.r > 0.8f && c.b > 0.8f && c.g < 0.2f) magenta += 1;
        }
    Stats s;
    s.mean = sum / n;
    s.spread = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
    s.magenta = magenta / n;
    return s;
}

double meanDifference(const Image& a, const Image& b, Region r) {
    double sum = 0;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const glm::vec4 d = glm::abs(a.at(x, y) - b.at(x, y));
            sum += (d.r + d.g + d.b) / 3.0;
        }
    return sum / (double(r.x1 - r.x0) * (r.y1 - r.y0));
}

class ViewerWindow : public ::testing::Test {
protected:
    void SetUp() override {
        if (runShell("which xvfb-run").exitCode != 0) GTEST_SKIP() << "xvfb-run is not installed";
        dir_ = fs::path(::testing::TempDir()) /
               ("voxlab_viewer_" + std::to_string(getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    CommandResult play(const std::string& script, const std::string& options = "") {
        std::ofstream(path("script.vs")) << script;
        return runShell("xvfb-run -a -s '-screen 0 1024x768x24' " + std::string(VOXLAB_BINARY) +
                            " view --script " + path("script.vs") + " --window-size 640x400 --student " +
                            std::string(VOXLAB_SOURCE_DIR) + "/assignments " + options,
                        240);
    }
    fs::path dir_;
};

TEST_F(ViewerWindow, AScriptedSessionShowsEveryPart) {
    const CommandResult r = play("load tooth.nrrd\n"
                                 "renderer mip\n"
                                 "panel tf off\n"
                                 "wait 2\n"
                                 "screenshot " + path("mip.png") + "\n"
                                 "split on\n"
                                 "implementation student\n"
                                 "panel controls off\n"
                                 "wait 2\n"
                                 "screenshot " + path("split.png") + "\n"
                                 "split difference\n"
                                 "wait 1\n"
                                 "screenshot " + path("difference.png") + "\n"
                                 "split off\n"
                                 "implementation reference\n"
                                 "panel controls on\n"
                                 "drag 5 0 4\n"
                                 "panel slices on\n"
                                 "panel profile on\n"
                                 "click 420 200\n"
                                 "wait 2\n"
                                 "screenshot " + path("panels.png") + "\n"
                                 "quit\n");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    // Dragging renders reduced images, then one at full quality (640x400).
    EXPECT_NE(r.out.find("drag: 3 frames"), std::string::npos) << r.out;  // the first step renders the first
    EXPECT_NE(r.out.find("idle, full quality 640x400"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("refinement step"), std::string::npos) << r.out;
    for (const char* name : {"mip.png", "split.png", "difference.png", "panels.png"}) {
        ASSERT_TRUE(fs::exists(path(name))) << name << "\n" << r.out << r.err;
        const Image img = loadPng(path(name));
        EXPECT_EQ(img.width, 640) << name;
        EXPECT_EQ(img.height, 400) << name;
    }
    // The MIP: a bright tooth in the middle, and the control panel (text on
    // a panel background) at the top left.
    const Image mip = loadPng(path("mip.png"));
    EXPECT_GT(stats(mip, {400, 120, 520, 280}).mean, 0.15) << "no volume in the middle";
    EXPECT_GT(stats(mip, {15, 15, 300, 120}).spread, 0.05) << "no panel at the top left";
    // The split: the student's stub shows the magenta checkerboard on the
    // left, the reference on the right does not.
    const Image split = loadPng(path("split.png"));
    EXPECT_GT(stats(split, {200, 150, 310, 250}).magenta, 0.2) << "the student side is not the stub";
    EXPECT_LT(stats(split, {330, 150, 440, 250}).magenta, 0.01) << "the reference side shows the stub";
    // The difference between stub and reference is large across the volume.
    EXPECT_GT(stats(loadPng(path("difference.png")), {250, 150, 390, 250}).mean, 0.3);
    // The slice and ray-profile panels open on the right half, over what
    // was the plain view, and the profile's plot has structure.
    const Image panels = loadPng(path("panels.png"));
    EXPECT_GT(meanDifference(panels, mip, {400, 0, 640, 400}), 0.08);
    EXPECT_GT(stats(panels, {400, 100, 620, 240}).spread, 0.05);
}

// The samples view colours each pixel by the samples its ray takes, on a
// fixed scale: with empty-space skipping the air around the bonsai goes
// dark, without it the whole box glows.
TEST_F(ViewerWindow, TheSamplesViewShowsWhatSkippingLeavesOut) {
    const CommandResult r = play("load bonsai.nrrd\n"
                                 "renderer composite\n"
                                 "tf tf/bonsai.json\n"
                                 "panel tf off\n"
                                 "panel controls off\n"
                                 "camera azimuth 35\n"
                                 "camera elevation 25\n"
                                 "wait 2\n"
                                 "screenshot " + path("image.png") + "\n"
                                 "samples on\n"
                                 "wait 2\n"
                                 "screenshot " + path("skipping.png") + "\n"
                                 "skipping off\n"
                                 "wait 2\n"
                                 "screenshot " + path("every_sample.png") + "\n"
                                 "quit\n");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const Image image = loadPng(path("image.png")), skipping = loadPng(path("skipping.png")),
                every = loadPng(path("every_sample.png"));
    // Right of the leaves, below the plate: air inside the box.
    const Region air = {420, 200, 500, 300};
    const double skipped = stats(skipping, air).mean, sampled = stats(every, air).mean;
    EXPECT_LT(skipped, 0.03) << "skipping should leave the air unsampled";
    EXPECT_GT(sampled, 0.1) << "without skipping every ray samples the air";
    EXPECT_GT(meanDifference(image, skipping, {0, 0, 640, 360}), 0.02) << "the samples view looks like the image";
}

TEST_F(ViewerWindow, ABadScriptOrDatasetIsAOneLineError) {
    std::ofstream(path("bad.vs")) << "renderer mip\nrotat 10 20\n";
    const CommandResult bad = runShell("xvfb-run -a " + std::string(VOXLAB_BINARY) + " view --script " +
                                       path("bad.vs"), 120);
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("bad.vs:2: unknown command 'rotat'"), std::string::npos) << bad.err;
    // A missing dataset in a script stops it with the script's line.
    const CommandResult missing = play("load no_such_volume.nrrd\nquit\n");
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_NE(missing.err.find("script.vs:1"), std::string::npos) << missing.err;
    EXPECT_NE(missing.err.find("no_such_volume.nrrd"), std::string::npos) << missing.err;
}

// A student release has no reference/: its split view compares a grading
// scene with the shipped expected image (rendered here by the grader from
// reference/, as tools/make_student_release.sh does), never with the
// student's own code. In difference mode a correct MIP shows (almost)
// black over the image, one whose maximum starts at 0 shows the air of the
// signed CT lit up; away from a grading scene it shows nothing to compare.
TEST_F(ViewerWindow, AStudentReleaseComparesWithTheExpectedImage) {
    const fs::path release = dir_ / "release";
    fs::create_directories(release / "assignments");
    for (const char* item : {"shaders", "framework", "datasets", "CMakeLists.txt"})
        fs::create_symlink(fs::path(VOXLAB_SOURCE_DIR) / item, release / item);
    fs::copy(fs::path(VOXLAB_SOURCE_DIR) / "assignments", release / "assignments", fs::copy_options::recursive);
    const CommandResult expected = runShell(std::string(VOXLAB_BINARY) + " grade --render-expected " +
                                                (release / "expected").string() + " --stage mip --quiet",
                                            240);
    ASSERT_EQ(expected.exitCode, 0) << expected.err;
    auto difference = [&](const std::string& find, const std::string& replace, const std::string& png) {
        std::string code;
        {
            std::ifstream in(fs::path(VOXLAB_SOURCE_DIR) / "reference/mip/mip.glsl");
            code.assign(std::istreambuf_iterator<char>(in), {});
        }
        if (!find.empty()) code.replace(code.find(find), find.size(), replace);
        std::ofstream(release / "assignments/mip/mip.glsl") << code;
        std::ofstream(path("release.vs")) << "load " << (release / "assignments/mip/scenes/headsq_hu_oblique.json").string()
                                          << "\npanel tf off\npanel controls off\nsplit difference\nwait 3\n"
                                          << "screenshot " << path(png) << "\nload bonsai.nrrd\nsplit on\nwait 2\n"
                                          << "screenshot " << path("away_" + png) << "\nquit\n";
        const CommandResult r = runShell("env VOXLAB_ROOT=" + release.string() +
                                             " xvfb-run -a -s '-screen 0 1024x768x24' " + std::string(VOXLAB_BINARY) +
                                             " view --script " + path("release.vs") + " --window-size 640x400",
                                         240);
        EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
        const Image shot = loadPng(path(png)), away = loadPng(path("away_" + png));
        // The 128x128 image letterboxed into 640x400: the square in the middle,
        // below the line that names the starter code's stubs (sampling's,
        // which this scene's hardware filtering never reaches).
        const Region square{120, 80, 520, 380};
        EXPECT_LT(stats(away, square).mean, 0.02) << "away from a grading scene nothing is compared";
        return stats(shot, square).mean;
    };
    const double correct = difference("", "", "correct.png");
    const double buggy = difference("float maximum = -3.4e38;", "float maximum = 0.0;", "buggy.png");
    std::printf("mean grey of the difference view: correct %.4f, maximum starting at 0 %.4f\n", correct, buggy);
    EXPECT_LT(correct, 0.01);
    EXPECT_GT(buggy, 0.2);
}

// A student release as tools/make_student_release.sh builds it, opened
// the ways its README says: the grading scene on the command line, as a
// path relative to the release and as an absolute one, and through the
// viewer's open field (the script's `load`, which takes the same path).
// Each time the split view (S) shows the starter code's checkerboard on the
// left and the scene's shipped expected image on the right, not the black
// "no reference" screen. (The release's voxlab is this build's, pointed at
// the release with VOXLAB_ROOT, as a build inside the release would be.)
TEST_F(ViewerWindow, AReleaseShowsTheExpectedImageHoweverTheSceneIsOpened) {
    const fs::path release = dir_ / "release";
    const CommandResult made = runShell("env VOXLAB_BUILD_DIR=" + fs::path(VOXLAB_BINARY).parent_path().parent_path().string() +
                                            " " + std::string(VOXLAB_SOURCE_DIR) + "/tools/make_student_release.sh " +
                                            release.string(),
                                        900);
    ASSERT_EQ(made.exitCode, 0) << made.out << made.err;
    const std::string scene = "assignments/mip/scenes/headsq_hu_oblique.json";
    ASSERT_TRUE(fs::exists(release / "expected/mip/headsq_hu_oblique.png"));
    auto view = [&](const std::string& name, const std::string& argument, const std::string& load) {
        std::ofstream(path(name + ".vs")) << load << "panel tf off\npanel controls off\nsplit on\nwait 3\nscreenshot "
                                          << path(name + ".png") << "\nquit\n";
        const CommandResult r = runShell("env -C " + release.string() + " VOXLAB_ROOT=" + release.string() +
                                             " xvfb-run -a -s '-screen 0 1024x768x24' " + std::string(VOXLAB_BINARY) +
                                             " view " + argument + " --script " + path(name + ".vs") +
                                             " --window-size 640x400",
                                         240);
        EXPECT_EQ(r.exitCode, 0) << name << ": " << r.out << r.err;
        return loadPng(path(name + ".png"));
    };
    const std::vector<std::pair<std::string, Image>> shots = {
        {"relative path", view("relative", scene, "")},
        {"absolute path", view("absolute", (release / scene).string(), "")},
        {"open field", view("opened", "", "load " + scene + "\n")}};
    // The 128x128 scene letterboxed into 640x400, split at the middle.
    const Region left{140, 90, 300, 370}, right{340, 90, 500, 370};
    for (const auto& [how, shot] : shots) {
        const Stats mine = stats(shot, left), expected = stats(shot, right);
        std::printf("%s: left magenta %.2f, right mean %.3f, magenta %.2f\n", how.c_str(), mine.magenta, expected.mean,
                    expected.magenta);
        EXPECT_GT(mine.magenta, 0.2) << how << ": the left side is not the starter code's stub";
        EXPECT_GT(expected.mean, 0.08) << how << ": the right side shows no expected image";
        EXPECT_GT(expected.spread, 0.05) << how << ": the right side shows no expected image";
        EXPECT_LT(expected.magenta, 0.01) << how << ": the right side shows the stub";
    }
}

// Pixels of one colour (within 0.12 per channel) in a region.
int countColour(const Image& img, Region r, glm::vec3 colour) {
    int n = 0;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const glm::vec3 d = glm::abs(glm::vec3(img.at(x, y)) - colour);
            if (std::max({d.r, d.g, d.b}) < 0.12f) ++n;
        }
    return n;
}

// A lecture's deck: five slides, each its own renderer, dataset, transfer
// function and caption, stepped by the arrow keys as a lecturer presses
// them (the key goes through GLFW's key callback, the same path a keyboard
// takes). Right at the last slide stays there; Left goes back; Home to the
// first, which looks as it did the first time.
TEST_F(ViewerWindow, ADeckOfFiveScenesStepsByArrowKey) {
    std::ofstream(path("talk.json")) << R"({"title": "test", "slides": [
      {"scene": {"dataset": "tooth.nrrd", "renderer": "mip"}, "caption": "one: MIP"},
      {"scene": {"dataset": "tooth.nrrd", "renderer": "composite", "transfer_function": "tf/tooth.json"},
       "caption": "two: compositing"},
      {"scene": {"dataset": "phantom:marschner-lobb:48", "renderer": "iso"}, "caption": "three: isosurface"},
      {"scene": {"dataset": "tooth.nrrd", "renderer": "slicer", "camera": {"view": "+z"}}, "caption": "four: a slice"},
      {"scene": {"dataset": "tooth.nrrd", "renderer": "tf2d", "tf2d": "tf2d/tooth.json"}, "caption": "five: 2D TF"}]})";
    std::string script;
    for (int i = 1; i <= 5; ++i) script += "screenshot " + path("s" + std::to_string(i) + ".png") + "\nkey right\n";
    script += "key left\nscreenshot " + path("back.png") + "\nkey home\nscreenshot " + path("home.png") + "\nquit\n";
    const CommandResult r = play(script, "--deck " + path("talk.json"));
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    // The slides in the order the keys chose; Right on the last one changes nothing.
    std::string order;
    for (std::size_t at = r.out.find("slide "); at != std::string::npos; at = r.out.find("slide ", at + 1))
        order += r.out.substr(at + 6, 1);
    EXPECT_EQ(order, "1234541") << r.out;
    EXPECT_NE(r.out.find("slide 3/5: iso: three: isosurface"), std::string::npos) << r.out;
    std::vector<Image> shots;
    for (int i = 1; i <= 5; ++i) shots.push_back(loadPng(path("s" + std::to_string(i) + ".png")));
    const Region image{0, 0, 640, 330}, caption{120, 330, 520, 380};
    for (int i = 1; i < 5; ++i) {
        EXPECT_GT(meanDifference(shots[i], shots[i - 1], image), 0.01) << "slide " << i + 1 << " looks like slide " << i;
        EXPECT_GT(meanDifference(shots[i], shots[i - 1], caption), 0.01) << "slide " << i + 1 << "'s caption";
    }
    for (const Image& shot : shots) EXPECT_GT(stats(shot, caption).spread, 0.1) << "no caption under the image";
    // (Not the status line: its render time differs from frame to frame.)
    const Region allButStatus{0, 0, 640, 370}, slideNumber{0, 370, 300, 400};
    for (const Region& r : {allButStatus, slideNumber}) {
        EXPECT_LT(meanDifference(loadPng(path("back.png")), shots[3], r), 0.003) << "Left after the end";
        EXPECT_LT(meanDifference(loadPng(path("home.png")), shots[0], r), 0.003) << "Home";
    }
    // A deck that names an unknown renderer fails before any window, naming the slide.
    std::ofstream(path("bad.json")) << R"({"slides": [{"scene": {"dataset": "tooth.nrrd", "renderer": "mpi"}}]})";
    const CommandResult bad = runShell(std::string(VOXLAB_BINARY) + " view --deck " + path("bad.json"), 60);
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("bad.json: slide 1: renderer 'mpi' is not known"), std::string::npos) << bad.err;
}

// A lecture on a machine without a GPU: at 1920x1080 and --ui-scale 2 a
// frame takes llvmpipe seconds, so the viewer renders it a band of rows per
// frame and the UI keeps drawing frames in between. Keys pressed while
// bands render, each pressed and released within one frame (two in one
// frame at the end), all take effect, in order: 2, 3, back to 2, 3, 4.
// (Before: a frame held the UI for the whole render, and a key pressed and
// released meanwhile was lost.)
TEST_F(ViewerWindow, KeysDuringA1080pRenderAllTakeEffect) {
    std::ofstream(path("talk.json")) << R"({"title": "busy", "slides": [
      {"scene": {"dataset": "bonsai.nrrd", "renderer": "composite", "transfer_function": "tf/bonsai.json"}, "caption": "one"},
      {"scene": {"dataset": "bonsai.nrrd", "renderer": "mip"}, "caption": "two"},
      {"scene": {"dataset": "tooth.nrrd", "renderer": "composite", "transfer_function": "tf/tooth.json"}, "caption": "three"},
      {"scene": {"dataset": "tooth.nrrd", "renderer": "mip"}, "caption": "four"}]})";
    std::ofstream(path("keys.vs")) << "rendering\npress right\nrendering\npress right\nrendering\npress left\n"
                                      "rendering\npress right right\nscreenshot " << path("last.png") << "\nquit\n";
    const CommandResult r = runShell("xvfb-run -a -s '-screen 0 1920x1080x24' " + std::string(VOXLAB_BINARY) +
                                         " view --deck " + path("talk.json") + " --script " + path("keys.vs") +
                                         " --window-size 1920x1080 --ui-scale 2",
                                     280);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    std::string order;
    for (std::size_t at = r.out.find("slide "); at != std::string::npos; at = r.out.find("slide ", at + 1))
        order += r.out.substr(at + 6, 1);
    EXPECT_EQ(order, "123234") << r.out;  // the first slide, then one per key
    // Every key came while an image was being rendered in bands, and the
    // UI drew frames meanwhile: many, each far shorter than the render.
    std::size_t during = 0;
    for (std::size_t at = r.out.find("press "); at != std::string::npos; at = r.out.find("press ", at + 1))
        during += r.out.compare(r.out.find(':', at), 17, ": while rendering") == 0;
    EXPECT_EQ(during, 4u) << r.out;
    const std::size_t timing = r.out.rfind("frames while rendering in bands: ");
    ASSERT_NE(timing, std::string::npos) << r.out;
    int frames = 0;
    double median = 0.0, longest = 0.0, image = 0.0;
    ASSERT_EQ(std::sscanf(r.out.c_str() + timing,
                          "frames while rendering in bands: %d, median %lf ms, longest %lf ms; the last image: %lf ms",
                          &frames, &median, &longest, &image), 4) << r.out;
    std::printf("%d frames while bands rendered: median %.1f ms, longest %.1f ms; the last 1080p image %.0f ms\n",
                frames, median, longest, image);
    EXPECT_GT(frames, 20) << r.out;
    // (Relative to the render, so that a loaded machine decides the same.)
    EXPECT_LT(median * 10.0, image) << "the UI waited for the render: " << r.out;
    const Image last = loadPng(path("last.png"));
    EXPECT_EQ(last.width, 1920);
    EXPECT_GT(stats(last, {700, 300, 1220, 800}).mean, 0.05) << "no image after the keys";
}

// Presentation mode: at --ui-scale 2 the control panel (its blue title bar)
// is twice as wide and twice as tall as at 1, and the + key grows it by a
// quarter. (A 1000x700 window: the panel at 2.25 still fits.)
TEST_F(ViewerWindow, TheUiScaleMakesThePanelsLarger) {
    const CommandResult r = play("size 1000 700\nload tooth.nrrd\nrenderer slicer\npanel tf off\nwait 1\nscreenshot " +
                                 path("one.png") + "\nui-scale 2\nwait 2\nscreenshot " + path("two.png") +
                                 "\nkey plus\nwait 2\nscreenshot " + path("more.png") + "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    // The title bar: ImGui's dark style draws it (0.16, 0.29, 0.48).
    auto titleBar = [&](const std::string& name) {
        const Image img = loadPng(path(name));
        int width = 0, height = 0;  // of the first band of such rows from the top
        for (int y = 0; y < img.height; ++y) {
            int row = 0;
            for (int x = 0; x < img.width; ++x) {
                const glm::vec4 c = img.at(x, y);
                if (std::abs(c.r - 0.16f) < 0.05f && std::abs(c.g - 0.29f) < 0.05f && std::abs(c.b - 0.48f) < 0.05f) ++row;
            }
            if (row > 20) ++height, width = std::max(width, row);
            else if (height > 0) break;
        }
        return std::pair<int, int>(width, height);
    };
    const auto [w1, h1] = titleBar("one.png");
    const auto [w2, h2] = titleBar("two.png");
    const auto [w3, h3] = titleBar("more.png");
    std::printf("title bar: %dx%d at 1, %dx%d at 2, %dx%d after +\n", w1, h1, w2, h2, w3, h3);
    ASSERT_GT(w1, 100);
    EXPECT_NEAR(double(w2) / w1, 2.0, 0.15);
    EXPECT_NEAR(double(h2) / h1, 2.0, 0.3);
    EXPECT_GT(w3, w2);
}

// Wireframes (the mesh's edges, texture slicing's proxy polygons) are drawn
// as wide as the UI's scale: at --ui-scale 3 the marching-cubes sphere's
// edges (grey 0.1) cover far more of it than at 1.
TEST_F(ViewerWindow, WireframesAreAsWideAsTheUiScale) {
    const CommandResult r = play("load phantom:sphere:24\nrenderer mesh\nparam wireframe true\npanel tf off\n"
                                 "panel controls off\nwait 2\nscreenshot " + path("one.png") + "\nui-scale 3\nwait 2\n"
                                 "screenshot " + path("three.png") + "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const Region sphere{280, 160, 360, 240};
    const int thin = countColour(loadPng(path("one.png")), sphere, glm::vec3(0.1f));
    const int wide = countColour(loadPng(path("three.png")), sphere, glm::vec3(0.1f));
    std::printf("edge pixels on the sphere: %d at scale 1, %d at scale 3\n", thin, wide);
    EXPECT_GT(thin, 100);
    EXPECT_GT(wide, 2 * thin) << "the lines did not grow with the UI's scale";
}

// P saves the window and says where: the full path, in a message and on the
// status line (a script prints it too); the file is there.
TEST_F(ViewerWindow, PSaysWhereTheScreenshotWent) {
    const fs::path folder = dir_ / "shots";
    fs::create_directories(folder);
    std::ofstream(path("p.vs")) << "load tooth.nrrd\nrenderer mip\npanel controls off\npanel tf off\nwait 1\nscreenshot "
                                << path("before.png") << "\nkey p\nwait 2\nscreenshot " << path("after.png") << "\nquit\n";
    const CommandResult r = runShell("env -C " + folder.string() + " xvfb-run -a -s '-screen 0 1024x768x24' " +
                                         std::string(VOXLAB_BINARY) + " view --script " + path("p.vs") +
                                         " --window-size 640x400",
                                     240);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const std::size_t at = r.out.find("screenshot saved: ");
    ASSERT_NE(at, std::string::npos) << r.out;
    const std::string saved = r.out.substr(at + 18, r.out.find('\n', at) - at - 18);
    EXPECT_TRUE(fs::path(saved).is_absolute()) << saved;
    EXPECT_EQ(fs::path(saved).parent_path(), folder) << saved;
    EXPECT_TRUE(fs::exists(saved)) << saved;
    // Over the status line, in green: the path (none before P).
    const Region above{0, 330, 640, 378};
    const glm::vec3 green(160 / 255.0f, 230 / 255.0f, 160 / 255.0f);
    EXPECT_EQ(countColour(loadPng(path("before.png")), above, green), 0);
    EXPECT_GT(countColour(loadPng(path("after.png")), above, green), 10) << "no path over the status line";
}

// The checkerboard explained: the student's starter code names its stubs in
// the terminal and over the image (amber text); the reference names none.
TEST_F(ViewerWindow, TheCheckerboardSaysWhichFunctionsAreMissing) {
    const CommandResult student = play("load tooth.nrrd\nrenderer mip\npanel tf off\npanel controls off\n"
                                       "implementation student\nwait 2\nscreenshot " + path("student.png") + "\nquit\n");
    ASSERT_EQ(student.exitCode, 0) << student.out << student.err;
    EXPECT_NE(student.err.find("not yet implemented"), std::string::npos) << student.err;
    EXPECT_NE(student.err.find("mip/: mip_ray()"), std::string::npos) << student.err;
    EXPECT_NE(student.err.find("voxlab check"), std::string::npos) << student.err;
    const CommandResult reference = play("load tooth.nrrd\nrenderer mip\npanel tf off\npanel controls off\n"
                                         "wait 2\nscreenshot " + path("reference.png") + "\nquit\n");
    ASSERT_EQ(reference.exitCode, 0) << reference.err;
    EXPECT_EQ(reference.err.find("not yet implemented"), std::string::npos) << reference.err;
    const Region banner{60, 0, 580, 60};
    const glm::vec3 amber(1.0f, 200 / 255.0f, 90 / 255.0f);
    EXPECT_GT(countColour(loadPng(path("student.png")), banner, amber), 30) << "no line over the image";
    EXPECT_EQ(countColour(loadPng(path("reference.png")), banner, amber), 0);
}

// The line names only the stubs the checkerboard's pixels reached, and only
// while it is on screen: with MIP done and sampling still the starter code,
// hardware filtering never calls sampling's functions (no checkerboard, no
// line); trilinear calls sample_trilinear() alone (not sample_nearest(),
// nor cubic's stubs, which the program also holds).
TEST_F(ViewerWindow, TheLineShowsOnlyWhileTheCheckerboardDoes) {
    const fs::path tree = dir_ / "tree";
    fs::copy(fs::path(VOXLAB_SOURCE_DIR) / "assignments", tree, fs::copy_options::recursive);
    fs::copy_file(fs::path(VOXLAB_SOURCE_DIR) / "reference/mip/mip.glsl", tree / "mip/mip.glsl",
                  fs::copy_options::overwrite_existing);
    const CommandResult r = play("load tooth.nrrd\nrenderer mip\npanel tf off\npanel controls off\nimplementation " +
                                 tree.string() + "\ninterpolation hardware\nwait 2\nscreenshot " + path("hardware.png") +
                                 "\ninterpolation trilinear\nwait 2\nscreenshot " + path("trilinear.png") + "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const Region banner{60, 0, 580, 60}, volume{250, 130, 390, 270};
    const glm::vec3 amber(1.0f, 200 / 255.0f, 90 / 255.0f);
    const Image hardware = loadPng(path("hardware.png")), trilinear = loadPng(path("trilinear.png"));
    EXPECT_LT(stats(hardware, volume).magenta, 0.01);
    EXPECT_EQ(countColour(hardware, banner, amber), 0) << "a line over an image without the checkerboard";
    EXPECT_GT(stats(trilinear, volume).magenta, 0.2);
    EXPECT_GT(countColour(trilinear, banner, amber), 30);
    // Said once, for trilinear, naming what its pixels ran.
    EXPECT_NE(r.err.find("not yet implemented: sampling/: sample_trilinear() ("), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("sample_nearest"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("cubic"), std::string::npos) << r.err;
}

// The ray profile's pixel is marked on the image while the camera is the
// one the profile was taken with.
TEST_F(ViewerWindow, ThePixelOfTheRayProfileIsMarked) {
    const CommandResult r = play("load tooth.nrrd\nrenderer mip\npanel tf off\npanel controls off\n"
                                 "panel profile on\nclick 200 150\nwait 2\nscreenshot " + path("marked.png") +
                                 "\nrotate 10 0\nwait 2\nscreenshot " + path("moved.png") + "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const glm::vec3 yellow(1.0f, 230 / 255.0f, 60 / 255.0f);
    const Region around{170, 120, 230, 180}, elsewhere{60, 240, 120, 300};
    EXPECT_GT(countColour(loadPng(path("marked.png")), around, yellow), 20) << "no marker at the clicked pixel";
    EXPECT_EQ(countColour(loadPng(path("marked.png")), elsewhere, yellow), 0);
    EXPECT_EQ(countColour(loadPng(path("moved.png")), around, yellow), 0) << "the marker outlived its camera";
}

// --keep-open: the script prepares the state, then the window stays for a
// person (here nobody comes, and the time limit ends it); without it the
// viewer closes at the end of the script.
TEST_F(ViewerWindow, KeepOpenLeavesTheWindowToThePersonAfterTheScript) {
    std::ofstream(path("prepare.vs")) << "load tooth.nrrd\nrenderer mip\nwait 1\n";
    const std::string view = "xvfb-run -a -s '-screen 0 1024x768x24' " + std::string(VOXLAB_BINARY) +
                             " view --window-size 320x240 --script " + path("prepare.vs");
    const CommandResult closes = runShell(view, 120);
    EXPECT_EQ(closes.exitCode, 0) << closes.err;
    const CommandResult stays = runShell(view + " --keep-open", 25);
    EXPECT_EQ(stays.exitCode, 124) << "the window closed by itself: " << stays.out << stays.err;
    const CommandResult alone = runShell(std::string(VOXLAB_BINARY) + " view --keep-open", 30);
    EXPECT_NE(alone.err.find("--keep-open goes with --script"), std::string::npos) << alone.err;
}

}  // namespace
}  // namespace voxlab::testing

// Clip planes in the viewer: the plane's outline and handle are drawn over
// the image, and dragging the handle along the arrow moves the plane along
// its normal (the kept side shrinks); a plane the scene does not have is a
// one-line error.
namespace voxlab::testing {
namespace {

TEST_F(ViewerWindow, AClipPlaneHandleDragsThePlaneAlongItsNormal) {
    std::ofstream(path("clip.json")) << R"({"dataset": "phantom:sphere:48", "renderer": "mip",
        "camera": {"azimuth": 30, "elevation": 20},
        "clip_planes": [{"point": [24, 24, 24], "normal": [1, 0, 0]}]})";
    const CommandResult r = play("scene " + path("clip.json") + "\npanel tf off\npanel controls off\nwait 2\nscreenshot " +
                                 path("before.png") + "\ndrag-plane 1 60 0\nwait 2\nscreenshot " + path("after.png") +
                                 "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const Image before = loadPng(path("before.png")), after = loadPng(path("after.png"));
    const glm::vec3 handle(1.0f, 200 / 255.0f, 60 / 255.0f);
    const Region all{0, 0, before.width, before.height};
    EXPECT_GT(countColour(before, all, handle), 50) << "no plane outline or handle drawn";
    // The sphere's visible part: grey pixels that are not the widget's colour.
    const auto lit = [&](const Image& img) {
        int n = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const glm::vec4 c = img.at(x, y);
                n += c.r > 0.2f && std::abs(c.r - c.b) < 0.05f;
            }
        return n;
    };
    std::printf("sphere pixels: %d before the drag, %d after\n", lit(before), lit(after));
    EXPECT_LT(lit(after), lit(before) * 0.8) << "dragging along the normal should cut more away";
    EXPECT_GT(lit(after), 100);
    const CommandResult bad = play("scene " + path("clip.json") + "\ndrag-plane 2 10 0\nquit\n");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("the scene has 1 clip planes"), std::string::npos) << bad.err;
}

// Levels of detail: bonsai (256^3) moves at its 128^3 level (the mean of
// each 2x2x2 block), at up to the window's size and twice the step, read
// with the GPU's filtering in place of the scene's trilinear,
// and the full level comes back once the mouse rests; tooth (1.6 million
// voxels) is small enough to move at full level, reduced as before. The
// coarse image is the same picture: near the full image, not blank.
TEST_F(ViewerWindow, MovingDrawsTheCoarseLevelAndRestDrawsTheVolume) {
    const CommandResult r = play("load bonsai.nrrd\n"
                                 "renderer mip\n"
                                 "panel controls off\n"
                                 "panel tf off\n"
                                 "wait 2\n"
                                 "screenshot " + path("before.png") + "\n"
                                 "drag 2 0 4\n"
                                 "screenshot " + path("after.png") + "\n"
                                 "load tooth.nrrd\n"
                                 "drag 2 0 3\n"
                                 "quit\n");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const std::size_t bonsai = r.out.find("drag: ");
    ASSERT_NE(bonsai, std::string::npos) << r.out;
    const std::string first = r.out.substr(bonsai, r.out.find('\n', bonsai) - bonsai);
    EXPECT_NE(first.find(", level 1, GPU filtering, step 1:"), std::string::npos) << first;
    EXPECT_NE(first.find("idle, full quality 640x400"), std::string::npos) << first;
    const std::size_t tooth = r.out.find("drag: ", bonsai + 1);
    ASSERT_NE(tooth, std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("level", tooth), std::string::npos) << r.out.substr(tooth);
    // The view turned 8 pixels' worth: the settled image is the bonsai, a
    // little turned, not the coarse one left behind.
    const Image before = loadPng(path("before.png")), after = loadPng(path("after.png"));
    EXPECT_GT(stats(after, {220, 100, 420, 300}).mean, 0.05) << "no volume after the drag";
    EXPECT_LT(meanDifference(before, after, {0, 0, 640, 400}), 0.05);
}

}  // namespace
}  // namespace voxlab::testing
