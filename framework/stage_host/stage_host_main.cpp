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
#include <tuple>
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

// Calls `f` on `call`'s arguments and appends its result to `out`; throws
// what the stage throws, and an Error naming a result too large to send.
template <class R, class... A>
void appendResult(std::string& out, R (*f)(A...), const char* name, const Call<A...>& call) {
    const R result = call.apply(f);
    if (const std::string why = Answer<R>::tooLarge(result); !why.empty())
        throw Error(std::string(name) + " returned " + why);
    Answer<R>::put(out, result);
}

// Serves one call of `f` (the library's, or null where it defines none):
// reads its arguments, calls it and answers with its result (the
// protocol: stage_host_protocol.h).
template <class R, class... A>
void serveCall(R (*f)(A...), const char* name) {
    Call<A...> call;
    if (!call.read(0)) _exit(0);
    answering([&] {
        if (!f) throw NotImplemented(name);
        std::string out = "O";
        appendResult(out, f, name, call);
        if (!sendAll(kAnswers, out.data(), out.size())) _exit(3);
    });
}

// Serves a batch of calls of `f`: a count <= kMaxBatch and the calls'
// arguments, read at once; the answer is every result, or the first
// failing call's error.
template <class R, class... A>
void serveBatch(R (*f)(A...), const char* name) {
    std::uint32_t count = 0;
    if (!readAll(0, &count, 4)) _exit(0);
    if (count > kMaxBatch) _exit(2);
    std::vector<char> wire(std::size_t(count) * Call<A...>::kWireSize + 1);
    if (!readAll(0, wire.data(), wire.size() - 1)) _exit(0);
    answering([&] {
        if (!f) throw NotImplemented(name);
        std::string out = "O";
        Call<A...> call;
        for (std::uint32_t i = 0; i < count; ++i) {
            call.load(wire.data() + std::size_t(i) * Call<A...>::kWireSize);
            appendResult(out, f, name, call);
        }
        if (!sendAll(kAnswers, out.data(), out.size())) _exit(3);
    });
}

// A batch's function (its op byte follows kBatch).
void serveBatchOf(const CppStages& stages) {
    unsigned char op = 0;
    if (!readAll(0, &op, 1)) _exit(0);
    switch (op) {
#define VOXLAB_STAGE_SERVE_BATCH(name, Result, Parameters) \
    case kOp_##name: serveBatch(stages.name, #name); break;
        VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_SERVE_BATCH)
#undef VOXLAB_STAGE_SERVE_BATCH
        default: _exit(2);
    }
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
        switch (static_cast<unsigned char>(op)) {
            case kBatch: serveBatchOf(stages); break;
#define VOXLAB_STAGE_SERVE(name, Result, Parameters) \
    case kOp_##name: serveCall(stages.name, #name); break;
            VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_SERVE)
#undef VOXLAB_STAGE_SERVE
            default: return 2;
        }
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
