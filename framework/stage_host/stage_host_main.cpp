// voxlab-stage-host: a submission's C++ stage in a process of its own
// (voxlab/stage_host.h). A program apart from `voxlab` on purpose: the
// voxlab executable holds the reference's compiled C++ stages, and a stage
// library loaded into it could find and call them in memory. This one
// holds no stage code at all; it confines itself, loads the library and
// answers the worker's calls.
#include <dlfcn.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "landlock.h"
#include "stage_host_protocol.h"
#include "voxlab/error.h"
#include "voxlab/stage_library.h"

namespace voxlab {

namespace {

using namespace stage_host;

void sendMessage(char status, const std::string& text) {
    const std::uint32_t length = std::uint32_t(std::min<std::size_t>(text.size(), kMaxMessage));
    if (!sendAll(kAnswers, &status, 1) || !sendAll(kAnswers, &length, 4) || !sendAll(kAnswers, text.data(), length))
        _exit(3);
}

// Runs `serve`, answering what the stage threw instead of a result.
template <class Serve>
void answering(Serve serve) {
    try {
        serve();
    } catch (const NotImplemented& e) {
        sendMessage('N', e.what());
    } catch (const std::exception& e) {
        sendMessage('E', e.what());
    } catch (...) {
        sendMessage('E', "the stage threw something that is not an exception");
    }
}

void serveCall(char op, const CppStages& stages) {
    double a[22];
    if (!readAll(0, a, std::size_t(argumentCount(op)) * sizeof(double))) _exit(0);
    answering([&] {
        if (op == 'P') {
            if (!stages.planeBoxPolygon) throw NotImplemented("planeBoxPolygon");
            std::vector<glm::dvec3> points = stages.planeBoxPolygon({a[0], a[1], a[2]}, a[3], {a[4], a[5], a[6]},
                                                                   {a[7], a[8], a[9]});
            if (points.size() > kMaxPoints) throw Error("planeBoxPolygon returned " + std::to_string(points.size()) + " points");
            const std::uint32_t count = std::uint32_t(points.size());
            if (!sendAll(kAnswers, "O", 1) || !sendAll(kAnswers, &count, 4) ||
                !sendAll(kAnswers, points.data(), count * sizeof(glm::dvec3)))
                _exit(3);
        } else if (op == 'A') {
            if (!stages.chooseSliceAxis) throw NotImplemented("chooseSliceAxis");
            const std::int32_t axis = stages.chooseSliceAxis({a[0], a[1], a[2]});
            if (!sendAll(kAnswers, "O", 1) || !sendAll(kAnswers, &axis, 4)) _exit(3);
        } else if (op == 'C') {
            if (!stages.cubeCase) throw NotImplemented("cubeCase");
            const std::int32_t bits = stages.cubeCase(a, a[8]);
            if (!sendAll(kAnswers, "O", 1) || !sendAll(kAnswers, &bits, 4)) _exit(3);
        } else if (op == 'W') {
            if (!stages.factorShearWarp) throw NotImplemented("factorShearWarp");
            const ShearWarp sw = stages.factorShearWarp(unpackCamera(a), glm::ivec3(int(a[16]), int(a[17]), int(a[18])),
                                                        {a[19], a[20], a[21]});
            double out[17] = {double(sw.axis), double(sw.front), sw.shear.x, sw.shear.y, sw.offset.x, sw.offset.y,
                              double(sw.size.x), double(sw.size.y)};
            for (int col = 0; col < 3; ++col)
                for (int row = 0; row < 3; ++row) out[8 + 3 * col + row] = sw.warp[col][row];
            if (!sendAll(kAnswers, "O", 1) || !sendAll(kAnswers, out, sizeof out)) _exit(3);
        } else if (op == 'S') {
            if (!stages.splatOrder) throw NotImplemented("splatOrder");
            const SplatOrder order = stages.splatOrder({a[0], a[1], a[2]});
            std::int32_t out[6];
            for (int k = 0; k < 3; ++k) out[k] = order.axes[std::size_t(k)], out[3 + k] = order.step[std::size_t(k)];
            if (!sendAll(kAnswers, "O", 1) || !sendAll(kAnswers, out, sizeof out)) _exit(3);
        } else {
            if (!stages.edgeCrossing) throw NotImplemented("edgeCrossing");
            const glm::dvec3 p = stages.edgeCrossing({a[0], a[1], a[2]}, {a[3], a[4], a[5]}, a[6], a[7], a[8]);
            if (!sendAll(kAnswers, "O", 1) || !sendAll(kAnswers, &p, sizeof p)) _exit(3);
        }
    });
}

// A batch ('c' cube cases, 'x' edge crossings): uint32 count <= kMaxBatch,
// then 8 doubles a call and the isovalue; the answer is 'O' and the count's
// results, or the first call's error.
void serveBatch(char op, const CppStages& stages) {
    std::uint32_t count = 0;
    if (!readAll(0, &count, 4)) _exit(0);
    if (count > kMaxBatch) _exit(2);
    std::vector<double> a(std::size_t(count) * 8 + 1);
    if (!readAll(0, a.data(), a.size() * sizeof(double))) _exit(0);
    const double isovalue = a.back();
    answering([&] {
        if (op == 'c') {
            if (!stages.cubeCase) throw NotImplemented("cubeCase");
            std::vector<std::int32_t> cases(count);
            for (std::uint32_t i = 0; i < count; ++i) cases[i] = stages.cubeCase(&a[8 * std::size_t(i)], isovalue);
            if (!sendAll(kAnswers, "O", 1) || !sendAll(kAnswers, cases.data(), cases.size() * 4)) _exit(3);
        } else {
            if (!stages.edgeCrossing) throw NotImplemented("edgeCrossing");
            std::vector<glm::dvec3> points(count);
            for (std::uint32_t i = 0; i < count; ++i) {
                const double* c = &a[8 * std::size_t(i)];
                points[i] = stages.edgeCrossing({c[0], c[1], c[2]}, {c[3], c[4], c[5]}, c[6], c[7], isovalue);
            }
            if (!sendAll(kAnswers, "O", 1) || !sendAll(kAnswers, points.data(), points.size() * sizeof(glm::dvec3)))
                _exit(3);
        }
    });
}

// Serves calls on stdin, answering on fd 3, until stdin closes.
int serve(const std::string& library) {
    // Reads: the library and what the dynamic loader needs; writes: none.
    const std::vector<const char*> readable = {library.c_str(), "/usr/lib", "/usr/local/lib", "/lib", "/lib64",
                                               "/etc/ld.so.cache"};
    const std::vector<const char*> devices = {"/dev/null", "/dev/zero", "/dev/urandom"};
    sandbox::restrictSelf(readable, {}, devices, true);
    close_range(kAnswers + 1, ~0U, 0);
    dup2(2, 1);
    void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = dlerror();
        throw Error(library + ": cannot load the stage library: " + (why ? why : "unknown error"));
    }
    auto get = reinterpret_cast<CppStages (*)()>(dlsym(handle, "voxlab_stage_library_functions"));
    if (!get) throw Error(library + ": not a voxlab stage library");
    const CppStages stages = get();
    signal(SIGPIPE, SIG_DFL);
    for (char op; readAll(0, &op, 1);) {
        if (op == 'c' || op == 'x') {
            serveBatch(op, stages);
            continue;
        }
        if (op != 'P' && op != 'A' && op != 'C' && op != 'X' && op != 'S' && op != 'W') return 2;
        serveCall(op, stages);
    }
    return 0;
}

}  // namespace

}  // namespace voxlab

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: voxlab-stage-host LIBRARY (started by voxlab grade-worker)\n");
        return 2;
    }
    try {
        return voxlab::serve(argv[1]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "voxlab-stage-host: %s\n", e.what());
        return 1;
    }
}
