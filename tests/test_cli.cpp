// The command line end to end: every subcommand, flags over scenes, and the
// error paths (one line on stderr, non-zero exit).
#include <gtest/gtest.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "support/run_command.h"
#include "voxlab/error.h"
#include "voxlab/image.h"
#include "voxlab/renderer.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("voxlab_cli_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(path(name), std::ios::binary) << text;
        return path(name);
    }
    // Expects failure with exactly one line on stderr containing `phrase`.
    void expectOneLineError(const std::string& args, const std::string& phrase) const {
        const CommandResult r = runVoxlab(args);
        EXPECT_NE(r.exitCode, 0) << args;
        EXPECT_EQ(lineCount(r.err), 1) << args << "\nstderr: " << r.err;
        EXPECT_NE(r.err.find(phrase), std::string::npos) << args << "\nstderr: " << r.err;
        EXPECT_EQ(r.err.rfind("voxlab: ", 0), 0u) << r.err;
    }
    fs::path dir_;
};

TEST_F(Cli, HelpWorksForEveryCommand) {
    for (const std::string cmd : {"render", "info", "list", "view", "compare", "grade", "check", "bench"}) {
        const CommandResult r = runVoxlab(cmd + " --help");
        EXPECT_EQ(r.exitCode, 0) << cmd;
        EXPECT_NE(r.out.find("usage: voxlab " + cmd), std::string::npos) << r.out;
    }
    const CommandResult r = runVoxlab("help");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("render"), std::string::npos);
}

TEST_F(Cli, RenderWritesTheMipAndPrintsItsPath) {
    const std::string out = path("shells.png");
    const CommandResult r = runVoxlab("render --dataset phantom:shells:32 --view +z --size 32x32 "
                                      "--interpolation nearest --step 1 --window 0,255 --out " + out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out, out + "\n");
    const Image img = loadPng(out);
    ASSERT_EQ(img.width, 32);
    ASSERT_EQ(img.height, 32);
    // Independent check: the maximum over z of the phantom's voxels.
    const Volume v = makePhantom("phantom:shells:32");
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            double m = 0;
            for (int z = 0; z < 32; ++z) m = std::max(m, v.value(x, y, z));
            ASSERT_NEAR(img.at(x, y).r * 255.0, m, 1.0) << "pixel " << x << "," << y;
        }
}

// The starter code's first picture is the checkerboard: render says which
// functions it stands for (the stubs its pixels ran), in one line; the
// reference, with nothing missing, says nothing on stderr. MIP's stub returns
// before it samples: sampling's stubs, compiled in, are never run and not
// named (with MIP done, trilinear sampling runs sample_trilinear() alone).
TEST_F(Cli, RenderOfStarterCodeNamesTheMissingFunctions) {
    const std::string common = "render --dataset phantom:sphere:16 --renderer mip --size 16x16 --out " + path("a.png");
    const CommandResult starter =
        runVoxlab(common + " --implementation " + std::string(VOXLAB_SOURCE_DIR) + "/assignments");
    ASSERT_EQ(starter.exitCode, 0) << starter.err;
    EXPECT_EQ(lineCount(starter.err), 1) << starter.err;
    EXPECT_NE(starter.err.find("mip/: mip_ray()"), std::string::npos) << starter.err;
    EXPECT_EQ(starter.err.find("sampling"), std::string::npos) << "a stub no pixel ran: " << starter.err;
    EXPECT_EQ(starter.err.find("composite"), std::string::npos) << "a stage the render did not use: " << starter.err;
    fs::create_directories(path("tree"));
    fs::copy(std::string(VOXLAB_SOURCE_DIR) + "/assignments", path("tree"), fs::copy_options::recursive);
    fs::copy_file(std::string(VOXLAB_SOURCE_DIR) + "/reference/mip/mip.glsl", path("tree") + "/mip/mip.glsl",
                  fs::copy_options::overwrite_existing);
    const CommandResult sampling = runVoxlab(common + " --interpolation trilinear --implementation " + path("tree"));
    EXPECT_NE(sampling.err.find("not yet implemented: sampling/: sample_trilinear() ("), std::string::npos) << sampling.err;
    const CommandResult reference =
        runVoxlab(common + " --implementation " + std::string(VOXLAB_SOURCE_DIR) + "/reference");
    ASSERT_EQ(reference.exitCode, 0) << reference.err;
    EXPECT_EQ(reference.err, "");
}

TEST_F(Cli, FlagsOverrideTheSceneFile) {
    const std::string scene = write("scene.json", R"({"dataset": "phantom:sphere:16", "renderer": "slicer",
        "size": [40, 30], "sampling": {"step": 0.25}, "parameters": {"offset": 2}})");
    const CommandResult r = runVoxlab("render " + scene + " --renderer mip --size 20x10 --print-scene");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("\"renderer\": \"mip\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("20"), std::string::npos);
    EXPECT_NE(r.out.find("0.25"), std::string::npos) << "the scene's step survives";
    // Rendering it for real: the slicer's offset parameter is unknown to mip.
    const CommandResult bad = runVoxlab("render " + scene + " --renderer mip --out " + path("x.png"));
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("parameter 'offset' is not declared"), std::string::npos) << bad.err;
}

TEST_F(Cli, RenderAcceptsEveryRendererAndBothProjections) {
    for (const auto& registered : rendererRegistry().all())
        for (const std::string proj : {"orthographic", "perspective"}) {
            const std::string renderer = registered->id();
            const std::string out = path(renderer + proj + ".png");
            const CommandResult r = runVoxlab("render --dataset phantom:marschner-lobb:24 --renderer " + renderer +
                                              " --projection " + proj + " --azimuth 30 --elevation 10 "
                                              "--size 48x32 --out " + out);
            // A renderer that cannot draw this projection says so, in the words it gives itself.
            Scene asked;
            asked.renderer = renderer;
            asked.camera.projection = parseProjection(proj);
            std::string refusal;
            try {
                registered->checkScene(asked, {});
            } catch (const Error& e) {
                refusal = e.what();
            }
            if (!refusal.empty()) {
                EXPECT_NE(r.exitCode, 0) << renderer << " " << proj;
                EXPECT_NE(r.err.find(refusal), std::string::npos) << r.err;
                EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
                continue;
            }
            ASSERT_EQ(r.exitCode, 0) << r.err;
            const Image img = loadPng(out);
            EXPECT_EQ(img.width, 48);
            EXPECT_EQ(img.height, 32);
            // Something was drawn: the image is not one flat colour.
            float brightest = 0, darkest = 1;
            for (float c : img.rgba) brightest = std::max(brightest, c), darkest = std::min(darkest, c);
            EXPECT_GT(brightest - darkest, 0.1f) << renderer << " " << proj << " rendered nothing";
        }
}

TEST_F(Cli, CompareReportsTheMetrics) {
    const std::string a = path("a.png"), b = path("b.png"), small = path("small.png");
    Image img(16, 16);
    savePng(img, a);
    img.set(3, 3, glm::vec4(1.0f));  // one pixel white: 1/256 of the pixels, 255 levels off
    savePng(img, b);
    savePng(Image(8, 8), small);
    const CommandResult same = runVoxlab("compare " + a + " " + a);
    ASSERT_EQ(same.exitCode, 0) << same.err;
    EXPECT_NE(same.out.find("PSNR:             inf"), std::string::npos) << same.out;
    const CommandResult differ = runVoxlab("compare " + a + " " + b);
    ASSERT_EQ(differ.exitCode, 0) << differ.err;
    EXPECT_NE(differ.out.find("max difference:   255.00"), std::string::npos) << differ.out;
    EXPECT_NE(differ.out.find("0.391% of pixels"), std::string::npos) << differ.out;
    expectOneLineError("compare " + a + " " + small, "images differ in size (16x16 and 8x8)");
}

TEST_F(Cli, InfoDescribesTheVolume) {
    const CommandResult r = runVoxlab("info cthead.nrrd");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("256 x 256 x 113"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("uint16"), std::string::npos);
    EXPECT_NE(r.out.find("spacing:  1 1 2"), std::string::npos);
    const Volume v = loadVolume(std::string(VOXLAB_SOURCE_DIR) + "/datasets/cthead.nrrd");
    char range[64];
    std::snprintf(range, sizeof range, "range:    %g .. %g", v.minValue(), v.maxValue());
    EXPECT_NE(r.out.find(range), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("histogram"), std::string::npos);
}

TEST_F(Cli, ListNamesEveryRendererWithItsParameters) {
    const CommandResult r = runVoxlab("list");
    ASSERT_EQ(r.exitCode, 0);
    for (const auto& renderer : rendererRegistry().all()) {
        EXPECT_NE(r.out.find(renderer->id() + " "), std::string::npos) << renderer->id();
        EXPECT_NE(r.out.find(renderer->description()), std::string::npos) << renderer->id();
        for (const ParameterSpec& p : renderer->parameters())
            EXPECT_NE(r.out.find("  " + p.name + " "), std::string::npos) << renderer->id() << " " << p.name;
    }
}

TEST_F(Cli, ErrorsAreOneLineWithANonZeroExit) {
    expectOneLineError("render --dataset " + path("missing.nrrd"), "missing.nrrd: no such file");
    // A mistyped submission folder must not quietly render the reference.
    expectOneLineError("render --dataset phantom:sphere:8 --out " + path("x.png") + " --implementation " +
                           path("no_such_folder"),
                       "no_such_folder' is not a folder");
    expectOneLineError("render --dataset phantom:sphere:8 --roi 1,2,3,4,5", "option --roi");
    expectOneLineError("render --dataset " +
                           write("trunc.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n\nabc"),
                       "trunc.nrrd: truncated data");
    expectOneLineError("render --dataset " +
                           write("huge.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 100000 100000 100000\n"
                                              "encoding: raw\n\nabc"),
                       "huge.nrrd");
    expectOneLineError("render --dataset phantom:sphere:8 --renderer nope", "unknown renderer 'nope'");
    expectOneLineError("render --dataset phantom:sphere:8 --frobnicate", "unknown option --frobnicate");
    expectOneLineError("render --dataset phantom:sphere:8 --size 10by10", "--size");
    expectOneLineError("render --dataset phantom:sphere:8 --view +w", "unknown view '+w'");
    expectOneLineError("render --dataset phantom:sphere:8 --window 5,1", "--window");
    expectOneLineError("render --dataset phantom:sphere:8 --param nope=1", "parameter 'nope' is not declared");
    expectOneLineError("render --dataset phantom:sphere:8 --step", "needs a value");
    expectOneLineError("render", "no dataset");
    expectOneLineError("render " + write("bad.json", "{\"dataset\": 3}"), "dataset");
    expectOneLineError("render " + write("typo.json", "{\"dataset\": \"phantom:sphere:8\", \"renderr\": \"mip\"}"),
                       "renderr");
    expectOneLineError("render --dataset phantom:sphere:8 --tf " + path("none.json"), "none.json");
    expectOneLineError("info " + write("junk.fld", "not an avs file"), "junk.fld");
    expectOneLineError("render --dataset phantom:sphere:8 --out /nonexistent/dir/x.png", "/nonexistent/dir/x.png");
    const CommandResult r = runVoxlab("frobnicate");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("unknown command"), std::string::npos);
}

// A save that fails is an error (it used to exit 0 with a truncated file):
// one line naming the file, a non-zero exit, and the old file untouched.
TEST_F(Cli, FailedSavesExitNonZeroAndKeepTheOldFile) {
    const std::string render = "render --dataset phantom:sphere:8 --size 8x8 --out ";
    expectOneLineError(render + "/dev/full", "/dev/full: cannot write: No space left on device");
    expectOneLineError("bench --dataset phantom:sphere:8 --size 8x8 --frames 1 --warmup 0 --sample-map /dev/full",
                       "/dev/full");
    // A folder where the image should go: refused, and what it holds is kept.
    fs::create_directories(dir_ / "taken.png");
    write("taken.png/inside", "kept");
    expectOneLineError(render + path("taken.png"), path("taken.png"));
    EXPECT_EQ(readFile(path("taken.png/inside")), "kept");
    // Over a file larger than a limit the new image exceeds (the shell's
    // ulimit -f, in 512-byte blocks; SIGXFSZ ignored so that the write fails).
    const std::string old(300, 'o');
    write("old.png", old);
    const CommandResult limited = runShell("sh -c 'trap \"\" XFSZ; ulimit -f 1; exec " + std::string(VOXLAB_BINARY) +
                                           " render --dataset phantom:shepp-logan:64 --size 256x256 --out " +
                                           path("old.png") + "'");
    EXPECT_NE(limited.exitCode, 0) << limited.out;
    EXPECT_EQ(lineCount(limited.err), 1) << limited.err;
    EXPECT_NE(limited.err.find(path("old.png") + ": cannot write: File too large"), std::string::npos) << limited.err;
    EXPECT_EQ(readFile(path("old.png")), old);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2) << "a temporary file is left";
}

TEST_F(Cli, BrokenStudentShaderIsReportedWithFileAndLine) {
    fs::create_directories(dir_ / "mip");
    write("mip/mip.glsl", "float mip_ray(Ray ray) {\n    return oops;\n}\n");
    const CommandResult r = runVoxlab("render --dataset phantom:sphere:8 --implementation " + dir_.string() +
                                      " --out " + path("x.png"));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("mip/mip.glsl:2:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("oops"), std::string::npos) << r.err;
}

// Every renderer runs unchanged on each headless backend. On this machine
// both are llvmpipe, so the images must agree exactly; where EGL has no
// display at all the test is skipped (the error must still be one line).
TEST_F(Cli, EglAndOsMesaRenderTheSameImage) {
    for (const std::string renderer : {"slicer", "mip"}) {
        const std::string args = "render --dataset tooth.nrrd --renderer " + renderer +
                                 " --azimuth 40 --elevation 30 --size 64x48 --out ";
        const CommandResult osmesa = runVoxlab(args + path("osmesa.png") + " --gl osmesa");
        ASSERT_EQ(osmesa.exitCode, 0) << osmesa.err;
        const CommandResult egl = runVoxlab(args + path("egl.png") + " --gl egl");
        if (egl.exitCode != 0) {
            EXPECT_EQ(lineCount(egl.err), 1) << egl.err;
            GTEST_SKIP() << "no EGL display here: " << egl.err;
        }
        const Image a = loadPng(path("osmesa.png")), b = loadPng(path("egl.png"));
        ASSERT_EQ(a.rgba.size(), b.rgba.size());
        float worst = 0;
        for (std::size_t i = 0; i < a.rgba.size(); ++i) worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
        EXPECT_LE(worst, 1.0f / 255.0f) << renderer;
    }
}

// A viewer script's screenshots are its output: one that cannot be saved
// ends the script with the error and a non-zero exit (it used to be a toast
// in a window nobody watches, and exit 0). So does --screenshot.
TEST_F(Cli, ViewerScreenshotThatCannotBeSavedFails) {
    if (runShell("which xvfb-run").exitCode != 0) GTEST_SKIP() << "xvfb-run is not installed";
    const std::string script = write("shots.txt", "wait 2\nscreenshot /dev/full\nscreenshot " + path("never.png") + "\n");
    const std::string viewer = "xvfb-run -a -s '-screen 0 640x480x24' " + std::string(VOXLAB_BINARY) +
                               " view --dataset phantom:sphere:16 --window-size 320x240 ";
    const CommandResult r = runShell(viewer + "--script " + script, 180);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("voxlab: /dev/full: cannot write: No space left on device\n"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("never.png"))) << "the script went on after the failed screenshot";
    const CommandResult once = runShell(viewer + "--frames 2 --screenshot /dev/full", 180);
    EXPECT_NE(once.exitCode, 0);
    EXPECT_NE(once.err.find("voxlab: /dev/full: cannot write: No space left on device\n"), std::string::npos)
        << once.err;
}

// The viewer in a real window under Xvfb: a scripted screenshot that shows
// the panel and a rendered volume.
TEST_F(Cli, ViewerScreenshotUnderXvfb) {
    if (runShell("which xvfb-run").exitCode != 0) GTEST_SKIP() << "xvfb-run is not installed";
    const std::string out = path("viewer.png");
    const CommandResult r =
        runShell("xvfb-run -a -s '-screen 0 1024x768x24' " + std::string(VOXLAB_BINARY) +
                     " view --dataset bucky.nrrd --window-size 640x480 --frames 3 --screenshot " + out,
                 180);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image img = loadPng(out);
    ASSERT_EQ(img.width, 640);
    ASSERT_EQ(img.height, 480);
    // The ImGui panel (top left) is neither black nor uniform; the volume
    // (centre right) has bright pixels.
    double panelSum = 0, panelMin = 1, panelMax = 0, bright = 0;
    for (int y = 15; y < 100; ++y)
        for (int x = 15; x < 300; ++x) {
            const float c = img.at(x, y).g;
            panelSum += c, panelMin = std::min<double>(panelMin, c), panelMax = std::max<double>(panelMax, c);
        }
    for (int y = 140; y < 340; ++y)
        for (int x = 380; x < 580; ++x) bright += img.at(x, y).r > 0.5f;
    EXPECT_GT(panelSum / (85.0 * 285.0), 0.05) << "no panel drawn";
    EXPECT_GT(panelMax - panelMin, 0.3) << "panel has no text";
    EXPECT_GT(bright, 100) << "no volume drawn";
}

// voxlab bench: N timed frames and the samples they take. From the +z axis
// view, orthographic, at one pixel per voxel and step 1, every ray through
// a 32^3 volume takes exactly 32 samples: 32 * 32 * 32 a frame.
TEST_F(Cli, BenchTimesFramesAndCountsSamples) {
    const CommandResult r = runVoxlab("bench --dataset phantom:sphere:32 --view +z --projection orthographic "
                                      "--size 32x32 --step 1 --turn 0 --frames 3 --warmup 1 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["frames"], 3);
    ASSERT_EQ(j["ms_per_frame"].size(), 3u);
    for (const auto& t : j["ms_per_frame"]) EXPECT_GT(t.get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(j["samples_per_frame"].get<double>(), 32.0 * 32.0 * 32.0);
    EXPECT_LE(j["q1_ms"].get<double>(), j["median_ms"].get<double>());
    EXPECT_LE(j["median_ms"].get<double>(), j["q3_ms"].get<double>());
    // Half the step doubles the samples (rounded per ray: 64 each).
    const CommandResult half = runVoxlab("bench --dataset phantom:sphere:32 --view +z --projection orthographic "
                                         "--size 32x32 --step 0.5 --turn 0 --frames 1 --warmup 0 --json");
    ASSERT_EQ(half.exitCode, 0) << half.err;
    EXPECT_DOUBLE_EQ(nlohmann::json::parse(half.out)["samples_per_frame"].get<double>(), 64.0 * 32.0 * 32.0);
    // Samples taken, counted on the GPU: the average reads every sample; compositing skips the
    // air around the sphere (the fallback ramp gives value 0 no opacity; at 64^3 the corner
    // bricks hold only air), and the sample map
    // shows it.
    const CommandResult average = runVoxlab("bench --dataset phantom:sphere:32 --renderer average --view +z "
                                            "--size 32x32 --step 1 --frames 1 --warmup 0 --json");
    ASSERT_EQ(average.exitCode, 0) << average.err;
    const nlohmann::json a = nlohmann::json::parse(average.out);
    EXPECT_EQ(a["samples_taken"].get<double>(), a["samples_per_frame"].get<double>());
    EXPECT_EQ(a["skipped_fraction"].get<double>(), 0.0);
    const std::string map = path("samples.png");
    const CommandResult composite = runVoxlab("bench --dataset phantom:sphere:64 --renderer composite --view +z "
                                              "--size 32x32 --step 1 --frames 1 --warmup 0 --json --sample-map " +
                                              map);
    ASSERT_EQ(composite.exitCode, 0) << composite.err;
    EXPECT_GT(nlohmann::json::parse(composite.out)["skipped_fraction"].get<double>(), 0.3);
    EXPECT_EQ(loadPng(map).width, 32);
    const CommandResult bad = runVoxlab("bench --dataset phantom:sphere:32 --frames 0");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("--frames"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace voxlab::testing
