// voxlab: the worker's side of the stage host: starting it, and the stubs
// that call it (see stage_host.h; the host itself is
// framework/stage_host/stage_host_main.cpp).
#include "voxlab/stage_host.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "stage_host_protocol.h"
#include "voxlab/error.h"
#include "voxlab/fd_io.h"
#include "voxlab/stage_library.h"

namespace voxlab {

namespace {

using namespace stage_host;

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

// The remote stand-in of the stage function with op `Op` and type R(A...):
// sends the call, waits for the answer and reads the result.
template <unsigned char Op, class F>
struct Remote;
template <unsigned char Op, class R, class... A>
struct Remote<Op, R(A...)> {
    static R call(A... a) {
        std::string message(1, char(Op));
        (Arg<A>::put(message, a), ...);
        Host& h = host();
        if (!sendAll(h.to, message.data(), message.size())) hostFailed();
        awaitAnswer();
        R result{};
        if (!Answer<R>::read(h.from, &result)) hostFailed();
        return result;
    }
    // The batch: up to kMaxBatch calls a round trip.
    static void run(const std::tuple<A...>* calls, std::size_t count, R* results) {
        Host& h = host();
        for (std::size_t first = 0; first < count; first += kMaxBatch) {
            const std::uint32_t n = std::uint32_t(std::min<std::size_t>(kMaxBatch, count - first));
            std::string message = {char(kBatch), char(Op)};
            message.append(reinterpret_cast<const char*>(&n), 4);
            for (std::size_t i = first; i < first + n; ++i)
                std::apply([&](const auto&... a) { (Arg<A>::put(message, a), ...); }, calls[i]);
            if (!sendAll(h.to, message.data(), message.size())) hostFailed();
            awaitAnswer();
            if (!Answer<R>::readMany(h.from, results + first, n)) hostFailed();
        }
    }
};

}  // namespace

std::string stageHostProgram() {
    char self[4096];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0) throw Error("cannot find the voxlab executable (/proc/self/exe), beside which voxlab-stage-host is");
    std::string path(self, std::size_t(n));
    path = path.substr(0, path.rfind('/') + 1) + "voxlab-stage-host";
    if (access(path.c_str(), X_OK) != 0) throw Error(path + ": missing (it is built and installed with voxlab)");
    return path;
}

void useStageHost(const std::string& program, const std::string& library, const std::vector<std::string>& functions) {
    int toHost[2], fromHost[2];
    if (pipe2(toHost, O_CLOEXEC) != 0 || pipe2(fromHost, O_CLOEXEC) != 0)
        throw Error(std::string("cannot start the stage host: ") + std::strerror(errno));
    std::vector<char*> argv = {const_cast<char*>(program.c_str()), const_cast<char*>(library.c_str()), nullptr};
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
    CppStageBatches batches{};
    for (const std::string& f : functions) {
        bool known = false;
#define VOXLAB_STAGE_ROUTE(name, Result, Parameters)                        \
    if (f == #name) {                                                       \
        routed.name = &Remote<kOp_##name, Result Parameters>::call;         \
        batches.name.run = &Remote<kOp_##name, Result Parameters>::run;     \
        known = true;                                                       \
    }
        VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_ROUTE)
#undef VOXLAB_STAGE_ROUTE
        if (!known) throw Error("'" + f + "' is not a C++ stage function");
    }
    overrideStageFunctions(routed);
    overrideStageBatches(batches);
}

}  // namespace voxlab
