// voxlab: child processes with limits (see child_process.h).
//
// An isolated child is started in two steps, because a PID namespace holds
// only the children of the process that made it:
//
//   grader ── fork ──> keeper: setsid, joins the pids cgroup, unshare(PID,
//                      net, IPC [, user]), forks, waits, mirrors the exit
//                        └── fork ──> worker: process 1 of the namespace;
//                                     limits, Landlock, exec
//
// The grader learns the worker's pid through a status pipe and kills the
// worker (not only the keeper's process group) at the time limit: when a
// namespace's process 1 dies, the kernel kills every process in it, however
// it detached itself. Between fork and exec only async-signal-safe calls are
// made; everything is prepared before fork.
#include "voxlab/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "landlock.h"
#include "voxlab/error.h"

namespace voxlab {

namespace {

namespace fs = std::filesystem;

void setLimit(int resource, std::size_t value) {
    if (value == 0) return;
    struct rlimit r;
    r.rlim_cur = r.rlim_max = rlim_t(value);
    setrlimit(resource, &r);
}

// Address sanitizer reserves terabytes of address space for its shadow
// memory, so an RLIMIT_AS cap would stop every sanitized child at start.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSpaceCapWorks = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSpaceCapWorks = false;
#else
constexpr bool kAddressSpaceCapWorks = true;
#endif
#else
constexpr bool kAddressSpaceCapWorks = true;
#endif

// Writes a decimal number (async-signal-safe).
void writeNumber(int fd, long value) {
    char buf[24];
    int n = 0;
    do {
        buf[sizeof buf - 1 - n++] = char('0' + value % 10);
        value /= 10;
    } while (value > 0 && n < 20);
    if (write(fd, buf + sizeof buf - n, std::size_t(n)) < 0) return;
}

// A pids cgroup for one child (root on a machine whose cgroups are
// writable): the kernel refuses fork() past pids.max. Empty when none can be
// made; removed by the destructor once the child and its namespace are gone.
class PidsCgroup {
public:
    explicit PidsCgroup(int maxProcesses) {
        static std::atomic<int> counter{0};
        if (maxProcesses <= 0) return;
        const std::string name = "voxlab-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
        for (const fs::path& base : ownCgroups()) {
            const fs::path dir = base / name;
            std::error_code ec;
            if (!fs::exists(base / "cgroup.procs", ec) || !fs::create_directory(dir, ec)) continue;
            std::ofstream max(dir / "pids.max");
            if (max << maxProcesses << "\n" && max.flush()) {
                dir_ = dir.string();
                procs_ = (dir / "cgroup.procs").string();
                return;
            }
            fs::remove(dir, ec);
        }
    }
    // Kills every process in the cgroup (what the PID namespace does where
    // there is one; without it, processes that left the process group with
    // setsid() are still here). Forks in between are caught by the repeats.
    void killAll() const {
        if (dir_.empty()) return;
        for (int round = 0; round < 50; ++round) {
            std::ifstream in(procs_);
            bool any = false;
            for (long pid; in >> pid;)
                if (pid > 0) any = true, kill(pid_t(pid), SIGKILL);
            if (!any) return;
            usleep(10000);
        }
    }
    ~PidsCgroup() {
        if (dir_.empty()) return;
        killAll();
        // The namespace's processes may take a moment to leave after a kill.
        for (int i = 0; i < 100 && rmdir(dir_.c_str()) != 0 && errno == EBUSY; ++i) usleep(10000);
    }
    const std::string& procs() const { return procs_; }

private:
    // This process's pids cgroup folder: cgroup v1's pids hierarchy, then
    // cgroup v2's unified one (from /proc/self/cgroup, "N:pids:/path").
    static std::vector<fs::path> ownCgroups() {
        std::vector<fs::path> found;
        std::ifstream in("/proc/self/cgroup");
        for (std::string line; std::getline(in, line);) {
            const std::size_t a = line.find(':'), b = line.find(':', a + 1);
            if (a == std::string::npos || b == std::string::npos) continue;
            const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
            if (controllers == "pids") found.insert(found.begin(), fs::path("/sys/fs/cgroup/pids") / path.substr(1));
            if (controllers.empty()) found.push_back(fs::path("/sys/fs/cgroup") / path.substr(1));
        }
        return found;
    }

    std::string dir_, procs_;
};

// Processes the calling (non-root) user has now, for an RLIMIT_NPROC that
// leaves the child `extra` more.
std::size_t userProcessLimit(int extra) {
    std::size_t count = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator("/proc", ec)) {
        struct stat st;
        const std::string name = entry.path().filename().string();
        if (!name.empty() && std::isdigit(static_cast<unsigned char>(name[0])) &&
            stat(entry.path().c_str(), &st) == 0 && st.st_uid == getuid())
            ++count;
    }
    return count + std::size_t(extra);
}

// Everything the child needs, prepared before fork.
struct Prepared {
    std::vector<char*> args, env;
    std::vector<std::string> envStrings;
    std::vector<const char*> readable, writable;
    std::vector<std::string> readableStrings;
    std::string uidMap, gidMap;
    std::size_t nproc = 0;
    int unshareFlags = 0;
};

// System folders any dynamically linked program (and Mesa) reads.
std::vector<std::string> systemReadable(const std::vector<std::string>& argv) {
    std::vector<std::string> paths = {"/usr", "/lib", "/lib64", "/lib32", "/bin", "/sbin", "/sys", "/proc/self",
                                      "/proc/cpuinfo", "/proc/meminfo", "/proc/stat", "/proc/sys/kernel",
                                      "/etc/ld.so.cache", "/etc/ld.so.conf", "/etc/ld.so.conf.d",
                                      "/etc/localtime", "/etc/drirc", "/etc/nsswitch.conf", "/etc/passwd",
                                      "/etc/group"};
    std::error_code ec;
    const fs::path program = fs::canonical(argv[0], ec);
    if (!ec) paths.push_back(program.parent_path().string());
    return paths;
}

Prepared prepare(const std::vector<std::string>& argv, const ChildLimits& limits) {
    Prepared p;
    for (const std::string& a : argv) p.args.push_back(const_cast<char*>(a.c_str()));
    p.args.push_back(nullptr);
    for (char** e = environ; *e; ++e) {
        const std::string entry = *e;
        if (!limits.environment.count(entry.substr(0, entry.find('=')))) p.envStrings.push_back(entry);
    }
    for (const auto& [key, value] : limits.environment) p.envStrings.push_back(key + "=" + value);
    for (std::string& e : p.envStrings) p.env.push_back(e.data());
    p.env.push_back(nullptr);
    for (const std::string& w : limits.writable) p.writable.push_back(w.c_str());
    if (limits.isolate) {
        p.readableStrings = systemReadable(argv);
        p.readableStrings.insert(p.readableStrings.end(), limits.readable.begin(), limits.readable.end());
        if (!limits.workingDir.empty()) p.readableStrings.push_back(limits.workingDir);
        for (const std::string& r : p.readableStrings) p.readable.push_back(r.c_str());
        p.unshareFlags = CLONE_NEWPID | CLONE_NEWNET | CLONE_NEWIPC;
        if (geteuid() != 0) {
            p.unshareFlags |= CLONE_NEWUSER;
            p.uidMap = std::to_string(geteuid()) + " " + std::to_string(geteuid()) + " 1\n";
            p.gidMap = std::to_string(getegid()) + " " + std::to_string(getegid()) + " 1\n";
            p.nproc = userProcessLimit(limits.maxProcesses);
        }
    }
    return p;
}

bool writeFile(const char* path, const std::string& text) {
    const int fd = open(path, O_WRONLY | O_CLOEXEC);
    if (fd < 0) return false;
    const bool ok = write(fd, text.data(), text.size()) == ssize_t(text.size());
    close(fd);
    return ok;
}

// Status bytes the keeper and the worker send to the grader.
enum Layer : unsigned {
    kSession = 1u << 8,
    kNamespaces = 1u << 9,
    kCgroup = 1u << 10,
    kNproc = 1u << 11,
};

// The worker's part, after fork: limits, confinement, exec. Never returns.
[[noreturn]] void becomeWorker(const Prepared& p, const ChildLimits& limits, int out, int results, int status,
                               unsigned layers) {
    if (limits.isolate) prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (status == 3) status = fcntl(status, F_DUPFD_CLOEXEC, 4);  // fd 3 is the results channel's
    const int nothing = open("/dev/null", O_RDONLY | O_CLOEXEC);  // the grader's stdin is not the child's
    if (nothing >= 0) dup2(nothing, 0);
    dup2(out, 1);
    dup2(out, 2);
    if (results >= 0) {
        if (results != 3) {
            dup2(results, 3);
        } else {
            const int flags = fcntl(3, F_GETFD);
            fcntl(3, F_SETFD, flags & ~FD_CLOEXEC);
        }
    }
    if (!limits.workingDir.empty() && chdir(limits.workingDir.c_str()) != 0) _exit(126);
    if (kAddressSpaceCapWorks) setLimit(RLIMIT_AS, limits.memoryBytes);
    setLimit(RLIMIT_FSIZE, limits.fileBytes);
    setLimit(RLIMIT_CORE, 1);  // 1 byte: no core dumps
    if (p.nproc > 0) {
        setLimit(RLIMIT_NPROC, p.nproc);
        layers |= kNproc;
    }
    if (limits.isolate || !p.writable.empty())
        layers |= sandbox::restrictSelf(p.readable, p.writable, limits.isolate);
    const unsigned char message[5] = {'L', static_cast<unsigned char>(layers),
                                      static_cast<unsigned char>(layers >> 8), 0, 0};
    if (write(status, message, sizeof message) != sizeof message) _exit(126);
    // No descriptor the grader happened to have open reaches the child.
    close_range(results >= 0 ? 4 : 3, ~0U, 0);
    execve(p.args[0], p.args.data(), p.env.data());
    const char msg[] = "cannot execute the program\n";
    if (write(2, msg, sizeof msg - 1) < 0) _exit(127);
    _exit(127);
}

// The keeper's part (isolated children): session, cgroup, namespaces, then
// the worker as process 1; exits as the worker did. Never returns.
[[noreturn]] void becomeKeeper(const Prepared& p, const ChildLimits& limits, const std::string& cgroupProcs,
                               int out, int results, int status) {
    unsigned layers = 0;
    if (setsid() >= 0) layers |= kSession;
    if (!cgroupProcs.empty()) {
        const int fd = open(cgroupProcs.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd >= 0) {
            writeNumber(fd, getpid());
            if (close(fd) == 0) layers |= kCgroup;
        }
    }
    if (unshare(p.unshareFlags) == 0) {
        layers |= kNamespaces;
        if (p.unshareFlags & CLONE_NEWUSER)
            if (!writeFile("/proc/self/setgroups", "deny") || !writeFile("/proc/self/uid_map", p.uidMap) ||
                !writeFile("/proc/self/gid_map", p.gidMap))
                _exit(126);
    }
    const pid_t worker = fork();
    if (worker < 0) _exit(126);
    if (worker == 0) becomeWorker(p, limits, out, results, status, layers);
    unsigned char message[5] = {'P', 0, 0, 0, 0};
    std::memcpy(message + 1, &worker, 4);
    if (write(status, message, sizeof message) != sizeof message) _exit(126);
    close(status);
    close(out);
    if (results >= 0) close(results);
    int waitStatus = 0;
    while (waitpid(worker, &waitStatus, 0) < 0 && errno == EINTR) {}
    if (WIFSIGNALED(waitStatus)) {
        signal(WTERMSIG(waitStatus), SIG_DFL);
        kill(getpid(), WTERMSIG(waitStatus));
    }
    _exit(WIFEXITED(waitStatus) ? WEXITSTATUS(waitStatus) : 126);
}

std::vector<std::string> layerNames(unsigned layers) {
    std::vector<std::string> names;
    const std::pair<unsigned, const char*> table[] = {
        {kSession, "own session"}, {kNamespaces, "pid, network and ipc namespaces"},
        {kCgroup, "pids cgroup"}, {kNproc, "process limit (RLIMIT_NPROC)"},
        {sandbox::kLandlockReads, "landlock reads"}, {sandbox::kLandlockWrites, "landlock writes"},
        {sandbox::kLandlockNetwork, "landlock network"}, {sandbox::kLandlockScopes, "landlock signal scope"}};
    for (const auto& [bit, name] : table)
        if (layers & bit) names.push_back(name);
    return names;
}

// Appends what is readable on `fd` to `text` (kept up to `cap` bytes);
// returns false at end of file.
bool drain(int fd, std::string& text, std::size_t cap, bool* truncated) {
    char buf[65536];
    const ssize_t n = read(fd, buf, sizeof buf);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) return true;
    if (n <= 0) return false;
    const std::size_t keep = std::min<std::size_t>(std::size_t(n), cap - std::min(cap, text.size()));
    text.append(buf, keep);
    if (keep < std::size_t(n) && truncated) *truncated = true;
    return true;
}

}  // namespace

bool sandboxAvailable() { return sandbox::landlockAbi() >= 1; }

std::vector<std::string> sandboxLayers() {
    static std::once_flag once;
    static std::vector<std::string> layers;
    std::call_once(once, [] {
        ChildLimits limits;
        limits.isolate = true;
        limits.seconds = 10;
        layers = runChild({"/bin/true"}, limits).sandbox;
    });
    return layers;
}

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
    const Prepared p = prepare(argv, limits);
    PidsCgroup cgroup(limits.isolate ? limits.maxProcesses : 0);
    int out[2], status[2], results[2] = {-1, -1};
    if (pipe2(out, O_CLOEXEC) != 0 || pipe2(status, O_CLOEXEC) != 0 ||
        (limits.resultsBytes > 0 && pipe2(results, O_CLOEXEC) != 0))
        throw Error("cannot start " + argv[0] + ": " + std::strerror(errno));
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid < 0) throw Error("cannot start " + argv[0] + ": " + std::strerror(errno));
    if (pid == 0) {
        close(out[0]);
        close(status[0]);
        if (results[0] >= 0) close(results[0]);
        if (limits.isolate) becomeKeeper(p, limits, cgroup.procs(), out[1], results[1], status[1]);
        setpgid(0, 0);
        becomeWorker(p, limits, out[1], results[1], status[1], 0);
    }
    if (!limits.isolate) setpgid(pid, pid);  // also here, so that a kill cannot race the child's own call
    // Readable when the child exits. It is this process's child, so the pid
    // cannot be reused before it is waited for.
    const int exitFd = int(syscall(SYS_pidfd_open, pid, 0));
    close(out[1]);
    close(status[1]);
    if (results[1] >= 0) close(results[1]);
    ChildResult result;
    // Status messages, 5 bytes each (written at once, so never split): the
    // worker's pid from the keeper ('P'), the layers in force ('L').
    pid_t workerPid = limits.isolate ? 0 : pid;
    for (int i = 0; i < (limits.isolate ? 2 : 1); ++i) {
        unsigned char message[5];
        if (read(status[0], message, sizeof message) != sizeof message) break;
        if (message[0] == 'P') std::memcpy(&workerPid, message + 1, 4);
        if (message[0] != 'L') continue;
        const unsigned layers = message[1] | (unsigned(message[2]) << 8);
        result.sandboxed = layers & sandbox::kLandlockWrites;
        result.sandbox = layerNames(layers);
    }
    close(status[0]);

    const auto deadline = start + std::chrono::duration<double>(limits.seconds);
    bool outOpen = true, resultsOpen = results[0] >= 0, exited = false;
    int waitStatus = 0;
    auto exitedAt = std::chrono::steady_clock::now();
    while (!exited || outOpen || resultsOpen) {
        const auto now = std::chrono::steady_clock::now();
        const double left = std::chrono::duration<double>(deadline - now).count();
        if (left <= 0.0 && !exited) {
            result.timedOut = true;
            if (workerPid > 0) kill(workerPid, SIGKILL);
            kill(-pid, SIGKILL);
            cgroup.killAll();
            waitpid(pid, &waitStatus, 0);
            exited = true;
            exitedAt = now;
        }
        // Descendants of a non-isolated child may hold the pipes open.
        if (exited && std::chrono::duration<double>(now - exitedAt).count() > 1.0) break;
        // The child's pidfd wakes the poll when it exits; without one (a
        // kernel before 5.3), a short wait once the pipes are closed.
        struct pollfd fds[3] = {{outOpen ? out[0] : -1, POLLIN, 0},
                                {resultsOpen ? results[0] : -1, POLLIN, 0},
                                {exited ? -1 : exitFd, POLLIN, 0}};
        const double wait = exitFd < 0 && !outOpen && !resultsOpen ? 0.005 : 0.1;
        if (poll(fds, 3, int(std::clamp(left, 0.0, wait) * 1000.0) + 1) > 0) {
            if (fds[0].revents) outOpen = drain(out[0], result.output, limits.outputBytes, nullptr);
            if (fds[1].revents)
                resultsOpen = drain(results[0], result.results, limits.resultsBytes, &result.resultsTruncated);
        }
        if (!exited && waitpid(pid, &waitStatus, WNOHANG) == pid) {
            exited = true;
            exitedAt = std::chrono::steady_clock::now();
            // The worker is gone, and with it its namespace; a non-isolated
            // child's leftovers go with its process group, and whatever
            // detached itself without a namespace with the cgroup.
            kill(-pid, SIGKILL);
            cgroup.killAll();
        }
    }
    close(out[0]);
    if (results[0] >= 0) close(results[0]);
    if (exitFd >= 0) close(exitFd);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!result.timedOut) {
        if (WIFEXITED(waitStatus)) result.exitCode = WEXITSTATUS(waitStatus);
        if (WIFSIGNALED(waitStatus)) result.signal = WTERMSIG(waitStatus);
    }
    return result;
}

}  // namespace voxlab
