// voxlab: the stage host and the worker's stubs that call it (see
// stage_host.h).
#include "voxlab/stage_host.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "landlock.h"
#include "voxlab/error.h"
#include "voxlab/fd_io.h"
#include "voxlab/stage_library.h"

namespace voxlab {

namespace {

constexpr std::uint32_t kMaxPoints = 64;      // a plane meets a box in at most 6
constexpr std::uint32_t kMaxMessage = 4096;
constexpr std::uint32_t kMaxBatch = 1u << 14;  // calls in one batch ('c', 'x')
// The host reads calls on stdin and answers on fd 3, so that what the
// stage prints (stdout, stderr) goes to the worker's log, not into answers.
constexpr int kAnswers = 3;

// Writes `size` bytes from `data` whole (fd_io.h).
bool sendAll(int fd, const void* data, std::size_t size) {
    return writeAll(fd, std::string_view(static_cast<const char*>(data), size)) == 0;
}

// --- The host. ---

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

int argumentCount(char op) { return op == 'P' ? 10 : op == 'A' || op == 'S' ? 3 : op == 'W' ? 22 : 9; }

// A camera and a grid as the 22 doubles of a 'W' call, and back.
void packShearWarpCall(const Camera& cam, glm::ivec3 dims, glm::dvec3 spacing, double* a) {
    const glm::dvec3 vectors[4] = {cam.position, cam.forward, cam.right, cam.down};
    for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) a[3 * v + k] = vectors[v][k];
    a[12] = cam.pixelScale, a[13] = cam.width, a[14] = cam.height;
    a[15] = cam.projection == Projection::Orthographic ? 0.0 : 1.0;
    for (int k = 0; k < 3; ++k) a[16 + k] = dims[k], a[19 + k] = spacing[k];
}

Camera unpackCamera(const double* a) {
    Camera cam;
    cam.position = {a[0], a[1], a[2]}, cam.forward = {a[3], a[4], a[5]};
    cam.right = {a[6], a[7], a[8]}, cam.down = {a[9], a[10], a[11]};
    cam.pixelScale = a[12], cam.width = int(a[13]), cam.height = int(a[14]);
    cam.projection = a[15] == 0.0 ? Projection::Orthographic : Projection::Perspective;
    return cam;
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

// --- The worker's stubs. ---

struct Host {
    int to = -1, from = -1;
    pid_t pid = 0;
    std::string library, died;
};

Host& host() {
    static Host h;
    return h;
}

// Every call after the host died says how it died.
[[noreturn]] void hostFailed() {
    Host& h = host();
    int status = 0;
    pid_t ended = h.pid > 0 ? waitpid(h.pid, &status, WNOHANG) : -1;
    if (ended == 0) {
        kill(h.pid, SIGKILL);  // alive but not answering: it ends here
        ended = waitpid(h.pid, &status, 0);
    }
    if (h.pid > 0 && ended == h.pid) {
        h.pid = 0;
        if (WIFSIGNALED(status)) h.died = std::string("the stage's C++ crashed (") + strsignal(WTERMSIG(status)) + ")";
        else h.died = "the stage's C++ ended its process (exit status " + std::to_string(WEXITSTATUS(status)) + ")";
    }
    throw StageCrashed(h.died.empty() ? "the stage's C++ (" + h.library + ") stopped answering" : h.died);
}

// Reads the answer's status; returns when it says the call succeeded.
void awaitAnswer() {
    Host& h = host();
    char status = 0;
    if (!readAll(h.from, &status, 1)) hostFailed();
    if (status == 'O') return;
    std::uint32_t length = 0;
    if ((status != 'N' && status != 'E') || !readAll(h.from, &length, 4) || length > kMaxMessage) hostFailed();
    std::string message(length, '\0');
    if (!readAll(h.from, message.data(), length)) hostFailed();
    if (status == 'N') throw NotImplemented(message.substr(0, message.find(' ')));
    throw Error(message);
}

// Sends a call; returns when the answer's status byte says it succeeded.
void call(char op, const double* args, int count) {
    Host& h = host();
    if (!sendAll(h.to, &op, 1) || !sendAll(h.to, args, std::size_t(count) * sizeof(double))) hostFailed();
    awaitAnswer();
}

// Sends a batch of `count` calls of 8 doubles each (kMaxBatch at a time).
template <class Answer>
void callBatch(char op, const double* args, std::size_t count, double isovalue, Answer* answers) {
    Host& h = host();
    for (std::size_t first = 0; first < count; first += kMaxBatch) {
        const std::uint32_t n = std::uint32_t(std::min<std::size_t>(kMaxBatch, count - first));
        if (!sendAll(h.to, &op, 1) || !sendAll(h.to, &n, 4) || !sendAll(h.to, args + 8 * first, n * 8 * sizeof(double)) ||
            !sendAll(h.to, &isovalue, sizeof isovalue))
            hostFailed();
        awaitAnswer();
        if (!readAll(h.from, answers + first, n * sizeof(Answer))) hostFailed();
    }
}

void remoteCubeCases(const double* values, std::size_t count, double isovalue, int* cases) {
    static_assert(sizeof(int) == sizeof(std::int32_t));
    callBatch('c', values, count, isovalue, cases);
}

void remoteEdgeCrossings(const EdgeCrossingCall* calls, std::size_t count, double isovalue, glm::dvec3* points) {
    std::vector<double> args(count * 8);
    for (std::size_t i = 0; i < count; ++i) {
        const EdgeCrossingCall& c = calls[i];
        const double packed[8] = {c.a.x, c.a.y, c.a.z, c.b.x, c.b.y, c.b.z, c.va, c.vb};
        std::copy(packed, packed + 8, &args[8 * i]);
    }
    callBatch('x', args.data(), count, isovalue, points);
}

std::vector<glm::dvec3> remotePlaneBoxPolygon(glm::dvec3 n, double d, glm::dvec3 lo, glm::dvec3 hi) {
    const double args[10] = {n.x, n.y, n.z, d, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z};
    call('P', args, 10);
    std::uint32_t count = 0;
    if (!readAll(host().from, &count, 4) || count > kMaxPoints) hostFailed();
    std::vector<glm::dvec3> points(count);
    if (!readAll(host().from, points.data(), count * sizeof(glm::dvec3))) hostFailed();
    return points;
}

int remoteChooseSliceAxis(glm::dvec3 v) {
    const double args[3] = {v.x, v.y, v.z};
    call('A', args, 3);
    std::int32_t axis = 0;
    if (!readAll(host().from, &axis, 4)) hostFailed();
    return axis;
}

int remoteCubeCase(const double values[8], double isovalue) {
    double args[9];
    std::copy(values, values + 8, args);
    args[8] = isovalue;
    call('C', args, 9);
    std::int32_t bits = 0;
    if (!readAll(host().from, &bits, 4)) hostFailed();
    return bits;
}

ShearWarp remoteFactorShearWarp(const Camera& camera, glm::ivec3 dims, glm::dvec3 spacing) {
    double args[22];
    packShearWarpCall(camera, dims, spacing, args);
    call('W', args, 22);
    double out[17];
    if (!readAll(host().from, out, sizeof out)) hostFailed();
    ShearWarp sw;
    sw.axis = int(out[0]), sw.front = int(out[1]);
    sw.shear = {out[2], out[3]}, sw.offset = {out[4], out[5]}, sw.size = {int(out[6]), int(out[7])};
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row) sw.warp[col][row] = out[8 + 3 * col + row];
    return sw;
}

SplatOrder remoteSplatOrder(glm::dvec3 d) {
    const double args[3] = {d.x, d.y, d.z};
    call('S', args, 3);
    std::int32_t out[6];
    if (!readAll(host().from, out, sizeof out)) hostFailed();
    SplatOrder order;
    for (int k = 0; k < 3; ++k) order.axes[std::size_t(k)] = out[k], order.step[std::size_t(k)] = out[3 + k];
    return order;
}

glm::dvec3 remoteEdgeCrossing(glm::dvec3 a, glm::dvec3 b, double va, double vb, double isovalue) {
    const double args[9] = {a.x, a.y, a.z, b.x, b.y, b.z, va, vb, isovalue};
    call('X', args, 9);
    glm::dvec3 p;
    if (!readAll(host().from, &p, sizeof p)) hostFailed();
    return p;
}

}  // namespace

int runStageHost(const std::string& library) {
    // Reads: the library and what the dynamic loader needs; writes: none.
    const std::vector<const char*> readable = {library.c_str(), "/usr", "/lib", "/lib64", "/etc/ld.so.cache"};
    sandbox::restrictSelf(readable, {}, true);
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

void useStageHost(const std::string& voxlab, const std::string& library, const std::vector<std::string>& functions) {
    int toHost[2], fromHost[2];
    if (pipe2(toHost, O_CLOEXEC) != 0 || pipe2(fromHost, O_CLOEXEC) != 0)
        throw Error(std::string("cannot start the stage host: ") + std::strerror(errno));
    std::vector<char*> argv = {const_cast<char*>(voxlab.c_str()), const_cast<char*>("stage-host"),
                               const_cast<char*>(library.c_str()), nullptr};
    const pid_t pid = fork();
    if (pid < 0) throw Error(std::string("cannot start the stage host: ") + std::strerror(errno));
    if (pid == 0) {
        dup2(toHost[0], 0);
        dup2(fromHost[1], kAnswers);
        execv(argv[0], argv.data());
        _exit(127);
    }
    close(toHost[0]);
    close(fromHost[1]);
    signal(SIGPIPE, SIG_IGN);  // a host that died is reported by the stubs, not by a signal
    Host& h = host();
    h = {toHost[1], fromHost[0], pid, library.substr(library.rfind('/') + 1), ""};
    CppStages routed{};
    for (const std::string& f : functions) {
        if (f == "planeBoxPolygon") routed.planeBoxPolygon = &remotePlaneBoxPolygon;
        else if (f == "chooseSliceAxis") routed.chooseSliceAxis = &remoteChooseSliceAxis;
        else if (f == "cubeCase") routed.cubeCase = &remoteCubeCase;
        else if (f == "edgeCrossing") routed.edgeCrossing = &remoteEdgeCrossing;
        else if (f == "splatOrder") routed.splatOrder = &remoteSplatOrder;
        else if (f == "factorShearWarp") routed.factorShearWarp = &remoteFactorShearWarp;
        else throw Error("'" + f + "' is not a C++ stage function");
    }
    overrideStageFunctions(routed);
    StageBatches batches{};
    if (routed.cubeCase) batches.cubeCases = &remoteCubeCases;
    if (routed.edgeCrossing) batches.edgeCrossings = &remoteEdgeCrossings;
    overrideStageBatches(batches);
}

}  // namespace voxlab
