// compare_slicing: ray casting ("composite") against 2D texture slicing
// ("texslice2d") and 3D texture slicing ("texslice3d") on real datasets with
// their transfer-function presets. For every dataset and view it renders a
// fine-step ray-cast reference (composite, step 0.125, no early
// termination), then each method: one warm-up render and then `repeats`
// timed renders (RenderEngine::render reads the image back, which waits for
// the GPU to finish: the time is the whole frame). It prints the median
// frame time and the image error against the reference: mean and worst
// per-pixel difference (the largest of the three colour channels, in grey
// levels 0..255) and PSNR over the colour channels.
//
// This is a benchmark, not a test: nothing is asserted. The numbers in
// docs/texture_slicing.md come from it.
//
//   compare_slicing [--size N] [--datasets bonsai,tooth,...] [--angles 0,20,45]
//                   [--elevation DEG] [--repeats N] [--reference-step S]
//                   [--perspective] [--early-termination T] [--out DIR] [--error-gain G]
//
// --out DIR writes every image as DIR/<dataset>_az<angle>_<method>.png, the
// reference as ..._reference.png, and each method's error image as
// ..._<method>_error.png: the per-pixel difference to the reference times G
// (default 8) as grey. Run with LP_NUM_THREADS set to fix llvmpipe's thread
// count.
//
// The methods run as a user would run them: composite keeps its default
// early termination (at opacity 0.99), so part of its error (at most 1% of
// what lies behind) is that speed-up's price; the slicers have none.
// --early-termination T sets it for the methods (1 turns it off: then only
// sampling differs from the reference).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "voxlab/error.h"
#include "voxlab/gl_context.h"
#include "voxlab/image.h"
#include "voxlab/render_engine.h"
#include "voxlab/scene.h"
#include "voxlab/stage_registry.h"
#include "voxlab/transfer_function.h"
#include "voxlab/volume.h"

namespace {

using namespace voxlab;

struct Options {
    int size = 512;
    std::vector<std::string> datasets = {"bonsai", "tooth", "cthead", "fuel"};
    std::vector<double> angles = {0.0, 20.0, 45.0};
    double elevation = 0.0;
    int repeats = 5;
    double referenceStep = 0.125;
    bool perspective = false;
    std::string out;
    double errorGain = 8.0;
    double earlyTermination = 0.99;
};

// One method under test: a renderer with its sampling setting.
struct Method {
    std::string label;     // as printed
    std::string renderer;  // voxlab renderer id
    double step = 1.0;     // composite, texslice3d
    int slicesPerVoxel = 0;  // texslice2d (0: not used)
};

const std::vector<Method> kMethods = {
    {"composite step 1", "composite", 1.0, 0},   {"composite step 0.5", "composite", 0.5, 0},
    {"texslice2d spv 1", "texslice2d", 1.0, 1},  {"texslice2d spv 2", "texslice2d", 1.0, 2},
    {"texslice3d step 1", "texslice3d", 1.0, 0}, {"texslice3d step 0.5", "texslice3d", 0.5, 0},
};

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

[[noreturn]] void usage(const std::string& problem) {
    std::cerr << "compare_slicing: " << problem << "\n"
              << "usage: compare_slicing [--size N] [--datasets a,b] [--angles 0,20,45] [--elevation DEG]\n"
              << "                       [--repeats N] [--reference-step S] [--perspective] [--out DIR]\n"
              << "                       [--early-termination T] [--error-gain G]\n";
    std::exit(2);
}

Options parseOptions(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--size") o.size = std::atoi(value().c_str());
        else if (arg == "--datasets") o.datasets = splitList(value());
        else if (arg == "--angles") {
            o.angles.clear();
            for (const std::string& a : splitList(value())) o.angles.push_back(std::atof(a.c_str()));
        } else if (arg == "--elevation") o.elevation = std::atof(value().c_str());
        else if (arg == "--repeats") o.repeats = std::atoi(value().c_str());
        else if (arg == "--reference-step") o.referenceStep = std::atof(value().c_str());
        else if (arg == "--perspective") o.perspective = true;
        else if (arg == "--out") o.out = value();
        else if (arg == "--error-gain") o.errorGain = std::atof(value().c_str());
        else if (arg == "--early-termination") o.earlyTermination = std::atof(value().c_str());
        else if (arg == "--help" || arg == "-h") usage("help");
        else usage("unknown argument '" + arg + "'");
    }
    if (o.size < 1 || o.size > kMaxImageSize) usage("--size must be in 1.." + std::to_string(kMaxImageSize));
    if (o.repeats < 1) usage("--repeats must be at least 1");
    if (!(o.referenceStep > 0.0)) usage("--reference-step must be positive");
    return o;
}

// Mean and worst per-pixel difference (largest channel of rgb, grey levels)
// and PSNR over the rgb channels, with the float images clamped to [0, 1].
struct ImageError {
    double mean = 0.0, max = 0.0, psnr = 0.0;
};

ImageError imageError(const Image& a, const Image& ref) {
    double sumPixel = 0.0, sumSquares = 0.0, worst = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            double pixel = 0.0;
            for (int ch = 0; ch < 3; ++ch) {
                const double e = std::clamp(double(a.at(x, y)[ch]), 0.0, 1.0) -
                                 std::clamp(double(ref.at(x, y)[ch]), 0.0, 1.0);
                pixel = std::max(pixel, std::abs(e));
                sumSquares += e * e;
            }
            sumPixel += pixel;
            worst = std::max(worst, pixel);
        }
    const double pixels = double(a.width) * a.height;
    ImageError err;
    err.mean = 255.0 * sumPixel / pixels;
    err.max = 255.0 * worst;
    const double mse = sumSquares / (3.0 * pixels);
    err.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : INFINITY;
    return err;
}

// |a - ref| (largest rgb channel) times `gain`, as grey.
Image errorImage(const Image& a, const Image& ref, double gain) {
    Image out(a.width, a.height);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            double e = 0.0;
            for (int ch = 0; ch < 3; ++ch) e = std::max(e, std::abs(double(a.at(x, y)[ch]) - ref.at(x, y)[ch]));
            const float g = float(std::min(1.0, gain * e));
            out.set(x, y, glm::vec4(g, g, g, 1.0f));
        }
    return out;
}

Scene makeScene(const Options& o, const TransferFunction& tf, double azimuth, const Method& m) {
    Scene scene;
    scene.renderer = m.renderer;
    scene.camera.view = "";  // orbit
    scene.camera.azimuth = azimuth;
    scene.camera.elevation = o.elevation;
    scene.camera.projection = o.perspective ? Projection::Perspective : Projection::Orthographic;
    scene.width = scene.height = o.size;
    scene.step = m.step;
    scene.interpolation = Interpolation::Trilinear;
    scene.transferFunction = tf;
    if (m.slicesPerVoxel > 0) scene.parameters["slices_per_voxel"] = m.slicesPerVoxel;
    if (m.renderer == "composite") scene.parameters["early_termination"] = o.earlyTermination;
    return scene;
}

double seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

std::string fileName(const std::string& dataset, double azimuth, const std::string& what) {
    std::string w = what;
    std::replace(w.begin(), w.end(), ' ', '_');
    std::ostringstream s;
    s << dataset << "_az" << azimuth << "_" << w << ".png";
    return s.str();
}

int run(const Options& o) {
    const std::unique_ptr<GlContext> context = createHeadlessContext();
    RenderEngine engine(rendererRegistry());
    const char* threads = std::getenv("LP_NUM_THREADS");
    std::printf("# %s; LP_NUM_THREADS=%s; %dx%d, %s, elevation %g; median of %d frames after 1 warm-up; "
                "composite early termination %g\n",
                context->description().c_str(), threads ? threads : "(unset)", o.size, o.size,
                o.perspective ? "perspective" : "orthographic", o.elevation, o.repeats, o.earlyTermination);
    std::printf("# error: against composite step %g without early termination; per-pixel difference = largest "
                "rgb channel, grey levels\n",
                o.referenceStep);
    std::printf("%-8s %5s  %-20s %10s %9s %9s %8s\n", "dataset", "az", "method", "time ms", "mean err", "max err",
                "PSNR dB");
    if (!o.out.empty()) std::filesystem::create_directories(o.out);

    for (const std::string& name : o.datasets) {
        const Volume volume = loadVolume(resolveDataPath(name + ".nrrd"));
        const TransferFunction tf = TransferFunction::load(resolveDataPath("tf/" + name + ".json"));
        engine.setVolume(volume);
        for (double azimuth : o.angles) {
            Method reference{"reference", "composite", o.referenceStep, 0};
            Scene refScene = makeScene(o, tf, azimuth, reference);
            refScene.parameters["early_termination"] = 1.0;  // exact: every sample counts
            const auto r0 = std::chrono::steady_clock::now();
            const Image ref = engine.render(refScene);
            const auto r1 = std::chrono::steady_clock::now();
            std::printf("%-8s %5g  %-20s %10.1f %9s %9s %8s\n", name.c_str(), azimuth,
                        ("composite step " + std::to_string(o.referenceStep).substr(0, 5)).c_str(),
                        1000.0 * seconds(r0, r1), "(ref)", "", "");
            if (!o.out.empty()) savePng(ref, o.out + "/" + fileName(name, azimuth, "reference"));

            for (const Method& m : kMethods) {
                const Scene scene = makeScene(o, tf, azimuth, m);
                Image img = engine.render(scene);  // warm-up: compiles the program, builds slice stacks
                std::vector<double> times;
                for (int i = 0; i < o.repeats; ++i) {
                    const auto t0 = std::chrono::steady_clock::now();
                    img = engine.render(scene);
                    const auto t1 = std::chrono::steady_clock::now();
                    times.push_back(seconds(t0, t1));
                }
                std::sort(times.begin(), times.end());
                const ImageError err = imageError(img, ref);
                std::printf("%-8s %5g  %-20s %10.1f %9.2f %9.1f %8.1f\n", name.c_str(), azimuth, m.label.c_str(),
                            1000.0 * times[times.size() / 2], err.mean, err.max, err.psnr);
                std::fflush(stdout);
                if (!o.out.empty()) {
                    savePng(img, o.out + "/" + fileName(name, azimuth, m.label));
                    savePng(errorImage(img, ref, o.errorGain),
                            o.out + "/" + fileName(name, azimuth, m.label + " error"));
                }
            }
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(parseOptions(argc, argv));
    } catch (const voxlab::Error& e) {
        std::cerr << "compare_slicing: " << e.what() << "\n";
        return 1;
    }
}
