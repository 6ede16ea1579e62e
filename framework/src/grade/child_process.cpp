// voxlab: child processes with limits (see child_process.h).
#include "voxlab/child_process.h"

#include <fcntl.h>
#include <linux/landlock.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>

#include "voxlab/error.h"

namespace voxlab {

namespace {

// Landlock (Documentation/userspace-api/landlock.rst): a process lists the
// access rights it wants the kernel to police ("handled"), grants some of
// them back beneath chosen folders, then restricts itself; the restriction
// is inherited across exec and cannot be undone. We police every right that
// changes the file system and grant them back beneath the writable folders.
// Reading and executing are not policed.
#ifndef SYS_landlock_create_ruleset
#define SYS_landlock_create_ruleset 444
#define SYS_landlock_add_rule 445
#define SYS_landlock_restrict_self 446
#endif
constexpr unsigned long long kWriteRightsV1 = (1ULL << 1) | (1ULL << 4) | (1ULL << 5) | (1ULL << 6) |
                                              (1ULL << 7) | (1ULL << 8) | (1ULL << 9) | (1ULL << 10) |
                                              (1ULL << 11) | (1ULL << 12);
constexpr unsigned long long kReferRight = 1ULL << 13;    // ABI 2
constexpr unsigned long long kTruncateRight = 1ULL << 14; // ABI 3

int landlockAbi() {
    const long abi = syscall(SYS_landlock_create_ruleset, nullptr, 0, LANDLOCK_CREATE_RULESET_VERSION);
    return abi < 0 ? 0 : int(abi);
}

// Runs in the child between fork and exec: only async-signal-safe calls.
bool confineWrites(const std::vector<const char*>& writable) {
    const int abi = landlockAbi();
    if (abi < 1) return false;
    unsigned long long handled = kWriteRightsV1;
    if (abi >= 2) handled |= kReferRight;
    if (abi >= 3) handled |= kTruncateRight;
    struct landlock_ruleset_attr attr;
    std::memset(&attr, 0, sizeof attr);
    attr.handled_access_fs = handled;
    const int ruleset = int(syscall(SYS_landlock_create_ruleset, &attr, sizeof attr, 0));
    if (ruleset < 0) return false;
    auto allow = [&](const char* path, unsigned long long rights) {
        const int fd = open(path, O_PATH | O_CLOEXEC);
        if (fd < 0) return false;
        struct landlock_path_beneath_attr rule;
        std::memset(&rule, 0, sizeof rule);
        rule.allowed_access = rights;
        rule.parent_fd = fd;
        const bool ok = syscall(SYS_landlock_add_rule, ruleset, LANDLOCK_RULE_PATH_BENEATH, &rule, 0) == 0;
        close(fd);
        return ok;
    };
    for (const char* path : writable)
        if (!allow(path, handled)) return false;
    // Opening device files for writing: /dev/null, and a GPU's render node.
    allow("/dev", 1ULL << 1);
    if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) return false;
    return syscall(SYS_landlock_restrict_self, ruleset, 0) == 0;
}

void setLimit(int resource, std::size_t bytes) {
    if (bytes == 0) return;
    struct rlimit r;
    r.rlim_cur = r.rlim_max = rlim_t(bytes);
    setrlimit(resource, &r);
}

}  // namespace

bool sandboxAvailable() { return landlockAbi() >= 1; }

std::string ChildResult::describe(double limitSeconds) const {
    char buf[64];
    if (timedOut) {
        std::snprintf(buf, sizeof buf, "timed out after %g s", limitSeconds);
        return buf;
    }
    if (signal != 0) return std::string("crashed (") + strsignal(signal) + ")";
    if (exitCode != 0) return "exit status " + std::to_string(exitCode);
    return "ok";
}

ChildResult runChild(const std::vector<std::string>& argv, const ChildLimits& limits) {
    if (argv.empty()) throw Error("runChild: no program given");
    // Everything the child needs is prepared before fork: after it, only
    // async-signal-safe calls are allowed.
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    std::vector<std::string> envStrings;
    for (char** e = environ; *e; ++e) {
        const std::string entry = *e;
        const std::string key = entry.substr(0, entry.find('='));
        if (!limits.environment.count(key)) envStrings.push_back(entry);
    }
    for (const auto& [key, value] : limits.environment) envStrings.push_back(key + "=" + value);
    std::vector<char*> env;
    for (std::string& e : envStrings) env.push_back(e.data());
    env.push_back(nullptr);
    std::vector<const char*> writable;
    for (const std::string& w : limits.writable) writable.push_back(w.c_str());

    int out[2], status[2];
    if (pipe2(out, O_CLOEXEC) != 0 || pipe2(status, O_CLOEXEC) != 0)
        throw Error("cannot start " + argv[0] + ": " + std::strerror(errno));
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid < 0) throw Error("cannot start " + argv[0] + ": " + std::strerror(errno));
    if (pid == 0) {
        setpgid(0, 0);
        dup2(out[1], 1);
        dup2(out[1], 2);
        if (!limits.workingDir.empty() && chdir(limits.workingDir.c_str()) != 0) _exit(126);
        setLimit(RLIMIT_AS, limits.memoryBytes);
        setLimit(RLIMIT_FSIZE, limits.fileBytes);
        setLimit(RLIMIT_CORE, 1);  // 1 byte: no core dumps
        char sandboxed = 0;
        if (!writable.empty()) sandboxed = confineWrites(writable) ? 1 : 0;
        if (write(status[1], &sandboxed, 1) != 1) _exit(126);
        execve(args[0], args.data(), env.data());
        const char msg[] = "cannot execute the program\n";
        if (write(2, msg, sizeof msg - 1) < 0) _exit(127);
        _exit(127);
    }
    setpgid(pid, pid);  // also here, so that a kill cannot race the child's own call
    close(out[1]);
    close(status[1]);
    ChildResult result;
    char sandboxed = 0;
    if (read(status[0], &sandboxed, 1) == 1) result.sandboxed = sandboxed != 0;
    close(status[0]);

    const auto deadline = start + std::chrono::duration<double>(limits.seconds);
    bool open = true;
    int waitStatus = 0;
    bool exited = false;
    while (!exited) {
        const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
        if (left <= 0.0) {
            result.timedOut = true;
            kill(-pid, SIGKILL);
            waitpid(pid, &waitStatus, 0);
            exited = true;
            break;
        }
        if (open) {
            struct pollfd p = {out[0], POLLIN, 0};
            const int ready = poll(&p, 1, int(std::min(left, 0.2) * 1000.0) + 1);
            if (ready > 0) {
                char buf[4096];
                const ssize_t n = read(out[0], buf, sizeof buf);
                if (n <= 0) open = false;
                else if (result.output.size() < limits.outputBytes)
                    result.output.append(buf, std::size_t(std::min<ssize_t>(n, limits.outputBytes - result.output.size())));
            }
        } else {
            usleep(20000);
        }
        if (waitpid(pid, &waitStatus, WNOHANG) == pid) exited = true;
    }
    // Whatever it started and left behind goes with it.
    kill(-pid, SIGKILL);
    for (char buf[4096]; open;) {
        struct pollfd p = {out[0], POLLIN, 0};
        if (poll(&p, 1, 0) <= 0) break;
        const ssize_t n = read(out[0], buf, sizeof buf);
        if (n <= 0) break;
        if (result.output.size() < limits.outputBytes)
            result.output.append(buf, std::size_t(std::min<ssize_t>(n, limits.outputBytes - result.output.size())));
    }
    close(out[0]);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!result.timedOut) {
        if (WIFEXITED(waitStatus)) result.exitCode = WEXITSTATUS(waitStatus);
        if (WIFSIGNALED(waitStatus)) result.signal = WTERMSIG(waitStatus);
    }
    return result;
}

}  // namespace voxlab
