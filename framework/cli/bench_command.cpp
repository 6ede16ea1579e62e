// voxlab bench: how fast a scene renders, frame after frame.
//
// After a warm-up (shader compilation, texture uploads), it renders N
// frames, turning the camera a little between frames so that nothing can be
// reused from the frame before, and prints the median and spread of the
// time per frame, and the samples per second: the samples the ray-casting
// renderers take by the README's rule (per pixel, floor(length / step + 1/2)
// over the part of the ray inside the box and the region of interest), and
// how many of those the shaders really took, counted on the GPU in one more
// frame (RenderEngine::countSamples): the rest were skipped, by empty-space
// skipping or early ray termination.
//
// Each frame is timed by the wall clock, from the first GL call to
// glFinish(), and by the GL's own clock: two GL_TIMESTAMP counters around
// the frame's commands (ARB_timer_query, core in 3.3), the first flushed at
// once so that the GL stamps it before the frame's work starts. On a GPU
// their difference is the GPU's time for the frame, without the CPU's part
// of it. (A GL_TIME_ELAPSED query measures the same on a GPU, but llvmpipe
// stamps it per 64x64 tile and keeps each thread's last tile, so it would
// say 20 ms for an 800 ms frame there: timestamps it is.) A driver whose
// timer counts no bits has no GPU time. A volume drawn in bricks also says
// how many bricks a frame drew and uploaded.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <sys/resource.h>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "voxlab/camera.h"
#include "voxlab/error.h"
#include "voxlab/flip.h"
#include "voxlab/gl_context.h"
#include "voxlab/gl_object.h"
#include "voxlab/ray_profile.h"
#include "voxlab/render_engine.h"
#include "voxlab/stage_registry.h"
#include "voxlab/volume.h"
#include "voxlab/volume_bricks.h"
#include "voxlab_gl.h"

namespace voxlab::cli {

namespace {

// The per-pixel counts (red channel) through the magma colour map, black
// for none, bright yellow for the most any pixel took (the largest count is
// printed, so that two maps can be compared).
void saveSampleMap(const Image& counts, const std::string& path) {
    float most = 0.0f;
    for (std::size_t i = 0; i < counts.rgba.size(); i += 4) most = std::max(most, counts.rgba[i]);
    Image map(counts.width, counts.height);
    for (std::size_t i = 0; i < counts.rgba.size(); i += 4) {
        const glm::vec3 c = magma(most > 0.0f ? counts.rgba[i] / most : 0.0);
        map.rgba[i] = c.r, map.rgba[i + 1] = c.g, map.rgba[i + 2] = c.b, map.rgba[i + 3] = 1.0f;
    }
    savePng(map, path);
    std::fprintf(stderr, "sample map: %s (brightest: %.0f samples)\n", path.c_str(), double(most));
}

double percentile(std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    const double at = p / 100.0 * double(v.size() - 1);
    const std::size_t i = std::size_t(at);
    return i + 1 < v.size() ? v[i] + (at - double(i)) * (v[i + 1] - v[i]) : v.back();
}

// The GL's clock around a frame (see the top of this file).
class GpuTimer {
public:
    GpuTimer() {
        GLint bits = 0;
        glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
        if (bits > 0) before_ = GlQuery::make(), after_ = GlQuery::make();
    }
    bool available() const { return before_.name() != 0; }
    void begin() const {
        if (available()) glQueryCounter(before_, GL_TIMESTAMP), glFlush();
    }
    void end() const {
        if (available()) glQueryCounter(after_, GL_TIMESTAMP);
    }
    // Milliseconds between the two stamps (waits for them).
    double milliseconds() const {
        GLuint64 from = 0, to = 0;
        if (!available()) return 0.0;
        glGetQueryObjectui64v(before_, GL_QUERY_RESULT, &from);
        glGetQueryObjectui64v(after_, GL_QUERY_RESULT, &to);
        return to > from ? double(to - from) * 1e-6 : 0.0;
    }

private:
    GlQuery before_, after_;
};

// What the bricks cost over the timed frames: passes drawn, bricks and
// bytes uploaded; and what the first frame of all (cold) and the last
// (the camera settled, when --turn is 0) uploaded.
struct BrickTraffic {
    std::size_t drawn = 0, uploads = 0, bytes = 0, firstFrameUploads = 0, lastFrameUploads = 0;
};

// The volume's textures: how many bricks, how many stay on the GPU, how
// many a frame drew and uploaded; and the process's peak memory.
nlohmann::json memoryFigures(const RenderEngine& engine, const Volume& volume, const BrickTraffic& t, int frames) {
    const BrickLayout& layout = engine.brickLayout();
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return {{"bricks", layout.bricks.size()},
            {"brick_grid", {layout.count.x, layout.count.y, layout.count.z}},
            {"bricks_resident", layout.resident},
            {"bricks_drawn_per_frame", double(t.drawn) / frames},
            {"brick_uploads_per_frame", double(t.uploads) / frames},
            {"brick_mib_uploaded_per_frame", double(t.bytes) / frames / double(1 << 20)},
            {"brick_uploads_first_frame", t.firstFrameUploads},
            {"brick_uploads_last_frame", t.lastFrameUploads},
            {"gpu_memory_budget_mib", double(layout.budgetBytes) / double(1 << 20)},
            {"volume_mib", double(volume.bytes().size()) / double(1 << 20)},
            {"peak_rss_mib", double(usage.ru_maxrss) / 1024.0}};
}

}  // namespace

namespace {

std::vector<OptionSpec> benchOptions() {
    std::vector<OptionSpec> specs = sceneOptions();
    specs.push_back({"frames", "N", "frames to time (default 10)"});
    specs.push_back({"warmup", "N", "frames rendered first and not timed (default 2)"});
    specs.push_back({"turn", "DEG", "azimuth added before each frame (default 0.5)"});
    specs.push_back({"json", "", "print the figures as JSON"});
    specs.push_back({"sample-map", "FILE.png", "save the samples each pixel took at the last view, as a heat map"});
    specs.push_back({"implementation", "DIR", "stage shaders from DIR instead of reference/ (a submission)"});
    specs.push_back({"gl", "BACKEND", "headless OpenGL: auto, osmesa, egl"});
    specs.push_back({"help", "", "show this help"});
    return specs;
}

// What a bench run measured.
struct BenchFigures {
    int frames = 0, warmup = 0;
    double turn = 0.0;
    std::vector<double> ms;             // each timed frame
    std::vector<double> gpuMs;          // the same by the GL's clock (none when it has no timer)
    bool counted = false;               // a ray caster whose samples are counted
    double samples = 0.0, full = 0.0;   // all frames', and the last frame's, by the sampling rule
    double taken = 0.0, skipped = 0.0;  // counted on the GPU at the last view
    nlohmann::json memory;
    std::string gl;
    double median() const { return percentile(ms, 50.0); }
    double samplesPerSecond() const {
        double totalMs = 0.0;
        for (double t : ms) totalMs += t;
        return counted && totalMs > 0 ? samples / (totalMs / 1000.0) : 0.0;
    }
};

// Renders warm-up and timed frames, turning the camera before each timed one.
void timeFrames(RenderEngine& engine, const Volume& volume, Scene& scene, BenchFigures& f) {
    CameraSpec& cam = scene.camera;
    const GpuTimer timer;
    BrickTraffic before, traffic;
    for (int i = 0; i < f.warmup + f.frames; ++i) {
        if (i >= f.warmup && f.turn != 0.0) {
            if (!cam.view.empty()) axisViewOrbitAngles(cam.view, &cam.azimuth, &cam.elevation), cam.view.clear();
            cam.azimuth += f.turn;
        }
        if (i == f.warmup) before = {engine.bricksDrawn(), engine.brickUploads(), engine.brickBytesUploaded()};
        const std::size_t uploads = engine.brickUploads();
        const auto t0 = std::chrono::steady_clock::now();
        timer.begin();
        engine.renderOffscreen(scene);
        timer.end();
        glFinish();
        const double elapsed = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (i == 0) traffic.firstFrameUploads = engine.brickUploads() - uploads;
        traffic.lastFrameUploads = engine.brickUploads() - uploads;
        if (i < f.warmup) continue;
        f.ms.push_back(elapsed);
        if (timer.available()) f.gpuMs.push_back(timer.milliseconds());
        if (f.counted) {
            f.full = samplesByRule(volume, scene);
            f.samples += f.full;
        }
    }
    traffic.drawn = engine.bricksDrawn() - before.drawn;
    traffic.uploads = engine.brickUploads() - before.uploads;
    traffic.bytes = engine.brickBytesUploaded() - before.bytes;
    f.memory = memoryFigures(engine, volume, traffic, f.frames);
}

// One more frame, untimed, at the last view: the samples the shaders
// actually took (with skipping and early termination), counted on the GPU.
void countTakenSamples(RenderEngine& engine, const Scene& scene, const Args& args, BenchFigures& f) {
    if (f.counted) {
        f.taken = engine.countSamples(scene);
        if (auto path = args.get("sample-map")) saveSampleMap(engine.readBack(), *path);
    } else if (args.get("sample-map")) {
        throw Error("option --sample-map: only ray-casting renderers without a cutting plane take samples");
    }
    f.skipped = f.full > 0.0 ? 1.0 - f.taken / f.full : 0.0;
    if (std::abs(f.skipped) < 5e-4) f.skipped = 0.0;  // rays grazing the box: a sample more or less
}

void printJson(const Scene& scene, const BenchFigures& f) {
    const double lowest = *std::min_element(f.ms.begin(), f.ms.end());
    const double highest = *std::max_element(f.ms.begin(), f.ms.end());
    nlohmann::json j = {{"dataset", scene.dataset},
                        {"renderer", scene.renderer},
                        {"width", scene.width},
                        {"height", scene.height},
                        {"step", scene.step},
                        {"frames", f.frames},
                        {"ms_per_frame", f.ms},
                        {"median_ms", f.median()},
                        {"q1_ms", percentile(f.ms, 25.0)},
                        {"q3_ms", percentile(f.ms, 75.0)},
                        {"min_ms", lowest},
                        {"max_ms", highest},
                        {"gpu_ms_per_frame", f.gpuMs},
                        {"gpu_median_ms", f.gpuMs.empty() ? nlohmann::json() : nlohmann::json(percentile(f.gpuMs, 50.0))},
                        {"gl", f.gl},
                        {"interpolation", interpolationName(scene.interpolation)},
                        {"skip_empty_space", scene.skipEmptySpace}};
    j.update(f.memory);
    if (f.counted) {
        j["samples_per_frame"] = f.samples / f.frames;
        j["samples_per_second"] = f.samplesPerSecond();
        j["samples_taken"] = f.taken;
        j["skipped_fraction"] = f.skipped;
    }
    std::cout << j.dump(2) << "\n";
}

void printText(const Scene& scene, const Volume& volume, const Renderer& renderer, const BenchFigures& f) {
    const double median = f.median(), q1 = percentile(f.ms, 25.0), q3 = percentile(f.ms, 75.0);
    const double lowest = *std::min_element(f.ms.begin(), f.ms.end());
    const double highest = *std::max_element(f.ms.begin(), f.ms.end());
    const std::string skipping = renderer.objectOrder() ? "n/a (slices)" : scene.skipEmptySpace ? "on" : "off";
    std::printf("%s, %s, %dx%d, step %g, %s interpolation, empty-space skipping %s, %d frames (after %d warm-up), "
                "camera turning %g deg a frame\n",
                volume.name().c_str(), scene.renderer.c_str(), scene.width, scene.height, scene.step,
                interpolationName(scene.interpolation), skipping.c_str(), f.frames, f.warmup, f.turn);
    std::printf("gl: %s\n", f.gl.c_str());
    std::printf("ms/frame: median %.1f (quartiles %.1f .. %.1f, min %.1f, max %.1f); %.2f frames/s\n", median, q1, q3,
                lowest, highest, median > 0 ? 1000.0 / median : 0.0);
    if (!f.gpuMs.empty()) {
        const double gpuMedian = percentile(f.gpuMs, 50.0);
        std::printf("GPU ms/frame (GL timestamps): median %.1f (quartiles %.1f .. %.1f); %.0f%% of the wall time\n",
                    gpuMedian, percentile(f.gpuMs, 25.0), percentile(f.gpuMs, 75.0),
                    median > 0 ? 100.0 * gpuMedian / median : 0.0);
    } else {
        std::printf("GPU ms/frame: n/a (the GL's timer counts no bits)\n");
    }
    const nlohmann::json& memory = f.memory;
    if (memory["bricks"].get<std::size_t>() > 1) {
        std::printf("bricks: %zu (%dx%dx%d), %zu on the GPU at once (budget %.0f MiB)\n",
                    memory["bricks"].get<std::size_t>(), memory["brick_grid"][0].get<int>(),
                    memory["brick_grid"][1].get<int>(), memory["brick_grid"][2].get<int>(),
                    memory["bricks_resident"].get<std::size_t>(), memory["gpu_memory_budget_mib"].get<double>());
        std::printf("bricks a frame: %.1f drawn, %.1f uploaded (%.1f MiB); the first frame uploaded %zu, the last %zu\n",
                    memory["bricks_drawn_per_frame"].get<double>(), memory["brick_uploads_per_frame"].get<double>(),
                    memory["brick_mib_uploaded_per_frame"].get<double>(),
                    memory["brick_uploads_first_frame"].get<std::size_t>(),
                    memory["brick_uploads_last_frame"].get<std::size_t>());
    }
    std::printf("memory: peak %.0f MiB resident (the volume: %.0f MiB)\n", memory["peak_rss_mib"].get<double>(),
                memory["volume_mib"].get<double>());
    if (f.counted) {
        std::printf("samples: %.3g a frame by the sampling rule, %.3g a second\n", f.samples / f.frames,
                    f.samplesPerSecond());
        std::printf("skipped: %.1f%% of them (%.3g taken; empty space and early termination)\n", 100.0 * f.skipped,
                    f.taken);
    }
}

}  // namespace

int benchCommand(int argc, char** argv) {
    const std::vector<OptionSpec> specs = benchOptions();
    const Args args(specs, argc, argv, 2, "bench");
    if (auto status = usageExit(args, false,
                                "usage: voxlab bench [SCENE.json] [--frames N] [--json] [scene options]\n\n"
                                "Renders the scene headless frame after frame, turning the camera a little between\n"
                                "frames, and prints the median and spread of the time per frame and, for the\n"
                                "ray-casting renderers, the samples per second and the share of them skipped (empty\n"
                                "space, early termination), counted on the GPU. See docs/performance.md.\n\n",
                                specs))
        return *status;
    Scene scene = sceneFromArgs(args, "bench");
    BenchFigures f;
    f.frames = args.get("frames") ? parseInt(*args.get("frames"), "--frames") : 10;
    f.warmup = args.get("warmup") ? parseInt(*args.get("warmup"), "--warmup") : 2;
    f.turn = args.get("turn") ? parseNumber(*args.get("turn"), "--turn") : 0.5;
    if (f.frames < 1 || f.frames > 100000) throw Error("option --frames: must be in 1..100000");
    if (f.warmup < 0 || f.warmup > 1000) throw Error("option --warmup: must be in 0..1000");
    const Renderer& renderer = rendererRegistry().get(scene.renderer);
    renderer.resolveParameters(scene.parameters);
    f.counted = samplesCountable(rendererRegistry(), scene);

    const Volume volume = loadVolume(scene.dataset);
    auto context = createHeadlessContext(parseHeadlessBackend(args.get("gl").value_or("auto")));
    f.gl = context->description();
    RenderEngine engine(rendererRegistry(), args.get("implementation").value_or(""));
    engine.setVolume(volume);
    timeFrames(engine, volume, scene, f);
    countTakenSamples(engine, scene, args, f);
    if (args.has("json")) printJson(scene, f);
    else printText(scene, volume, renderer, f);
    return 0;
}

}  // namespace voxlab::cli
