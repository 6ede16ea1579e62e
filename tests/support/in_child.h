// Test support: running code in a forked child under a resource limit, for
// tests that must see how voxlab fails when memory or file size runs out
// without putting the test process itself at risk.
#pragma once

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <exception>
#include <functional>
#include <new>
#include <string>

#include "voxlab/error.h"

namespace voxlab::testing {

// Runs `limit` (which sets the child's limits and returns whether it could)
// and then `body` in a forked child. Returns what `body` returned, or the
// message of what it threw: a voxlab::Error's own, "std::bad_alloc", or
// "not a voxlab::Error: ..."; "setrlimit failed" when `limit` returned
// false; "killed by signal N" or "exit status N" when the child did not
// finish normally.
inline std::string messageInChild(const std::function<bool()>& limit, const std::function<std::string()>& body) {
    int fds[2];
    if (::pipe(fds) != 0) return "pipe failed";
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(fds[0]);
        std::string message = "setrlimit failed";
        if (limit()) {
            try {
                message = body();
            } catch (const Error& e) {
                message = e.what();
            } catch (const std::bad_alloc&) {
                message = "std::bad_alloc";
            } catch (const std::exception& e) {
                message = std::string("not a voxlab::Error: ") + e.what();
            }
        }
        const ssize_t ignored = ::write(fds[1], message.data(), message.size());
        (void)ignored;
        ::_exit(0);
    }
    ::close(fds[1]);
    std::string message;
    char buf[4096];
    for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) message.append(buf, std::size_t(n));
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return "exit status " + std::to_string(WEXITSTATUS(status));
    return message;
}

}  // namespace voxlab::testing
