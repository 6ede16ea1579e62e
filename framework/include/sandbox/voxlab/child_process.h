// voxlab: running untrusted work in a child process with limits.
//
// The grader runs each submission's stage in its own process: a shader that
// loops forever, a crash or a runaway allocation then costs that stage only.
// runChild() starts a program with a wall-clock limit, an address-space cap
// and a file-size cap, and collects what it prints.
//
// With `isolate`, the child is also boxed in, default deny, with every layer
// this machine offers (ChildResult::sandbox lists those in force, and
// ChildResult::sandboxMissing those it lacks):
//   - its own session, and new user, PID, network, IPC, UTS and mount
//     namespaces: the child is process 1 of its PID namespace, so when it
//     ends, or is killed at the time limit, the kernel ends everything it
//     started, also children that called setsid(); it cannot name, let alone
//     signal, any process outside; it has no network, not even loopback;
//   - no privilege: no capability (the bounding, ambient, permitted and
//     effective sets emptied, root's exec rules locked off) and
//     PR_SET_NO_NEW_PRIVS, also when the grader runs as root;
//   - a system-call allow-list (seccomp, syscall_filter.cpp): everything the
//     compiler, the renderer and the stage host do not need fails with
//     EPERM (sockets, keyrings, mount, bpf, io_uring, ptrace, real-time
//     scheduling, raising priority, ...);
//   - an environment built from an allow-list (the locale, Mesa's and the
//     GL vendor's settings, voxlab's own paths) plus `environment`: nothing
//     else of the grader's (tokens, SSH_AUTH_SOCK) reaches it;
//   - one cgroup (ChildCgroup) for it and everything it starts: pids.max,
//     and memory.max with no swap, so memfds and children count against the
//     same cap; without cgroups, RLIMIT_NPROC (not applied to root) and the
//     per-process caps below are what is left, and the report says so;
//   - Landlock (Linux 5.13+): reads confined to `readable` plus the system
//     folders a program needs (/usr, /lib, /proc/self, /sys, ...), writes to
//     `writable` (empty: nowhere), devices to /dev/null, zero, urandom and a
//     GPU's render nodes (no block device, no /dev/kmsg); from Landlock ABI
//     4 no TCP connect or bind, from ABI 6 no signals to and no abstract
//     UNIX sockets of processes outside the sandbox;
//   - `scratch`: a tmpfs of `scratchBytes` mounted over that folder, so what
//     a build writes there is bounded as a whole (and vanishes with it);
//   - per process: RLIMIT_AS (`memoryBytes`), RLIMIT_FSIZE (`fileBytes`),
//     no core dumps.
//
// Results channel: with `resultsBytes` > 0 the child finds the write end of
// a pipe as file descriptor 3, and what it writes there (up to that many
// bytes) comes back in ChildResult::results. The parent reads it directly;
// the child has no file of the parent's to write results into.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace voxlab {

class ChildCgroup;

struct ChildLimits {
    double seconds = 60.0;             // wall clock; then everything it started is killed
    std::size_t memoryBytes = 0;       // RLIMIT_AS, and with isolate the cgroup's cap; 0: unchanged
    std::size_t fileBytes = 0;         // RLIMIT_FSIZE (largest file it may write); 0: unchanged
    std::size_t outputBytes = 1 << 20; // what is kept of its stdout + stderr
    std::size_t resultsBytes = 0;      // > 0: fd 3 is the results channel (see above)
    std::string workingDir;            // empty: the parent's
    bool isolate = false;              // namespaces, process limit, Landlock reads (see above)
    int maxProcesses = 64;             // with isolate: processes and threads it may have at once
    std::vector<std::string> readable; // with isolate: folders or files it may read
    std::vector<std::string> writable; // folders it may write (with isolate, or when non-empty)
    std::string scratch;               // with isolate: a folder to mount a size-capped tmpfs over
    std::size_t scratchBytes = 256u << 20;
    const ChildCgroup* cgroup = nullptr;  // with isolate: a cgroup shared with other children (else its own)
    // Added to (or replacing in) the environment: with isolate, the
    // allow-listed part of the parent's; without, all of the parent's.
    std::map<std::string, std::string> environment;
};

// One cgroup for one or more children run one after another (a stage's
// build and its run): everything they start counts against one process
// count and one memory cap (memory.max and no swap; cgroup v2, or v1's
// memory and pids hierarchies). Made where this process may make cgroups
// (root, or a delegated subtree); otherwise it limits nothing and says so.
// The destructor kills whatever is left in it and removes it.
class ChildCgroup {
public:
    ChildCgroup(int maxProcesses, std::size_t memoryBytes);
    ~ChildCgroup();
    ChildCgroup(const ChildCgroup&) = delete;
    ChildCgroup& operator=(const ChildCgroup&) = delete;

    bool limitsProcesses() const { return !pidsDir_.empty(); }
    bool limitsMemory() const { return !memoryDir_.empty(); }
    // The cgroup.procs files a child joins (async-signal-safe to write).
    const std::vector<std::string>& procsFiles() const { return procs_; }
    void killAll() const;
    // Processes the kernel killed for the memory cap since it was made.
    long oomKills() const;

private:
    std::string pidsDir_, memoryDir_;
    std::vector<std::string> procs_, dirs_;
    bool v2_ = false;  // the memory controller is cgroup v2's
};

struct ChildResult {
    int exitCode = -1;     // when it exited normally
    int signal = 0;        // when a signal ended it (after a timeout: SIGKILL)
    bool timedOut = false;
    bool sandboxed = false;  // Landlock confinement was in force
    std::vector<std::string> sandbox;  // the layers in force ("pid namespace", "landlock reads", ...)
    std::vector<std::string> sandboxMissing;  // the layers this machine could not give (isolate)
    bool outOfMemory = false;  // the cgroup's memory cap ended a process of it
    double seconds = 0.0;
    std::string output;    // stdout and stderr, interleaved, possibly truncated
    std::string results;   // what it wrote to fd 3 (resultsBytes > 0)
    bool resultsTruncated = false;

    bool succeeded() const { return !timedOut && signal == 0 && exitCode == 0; }
    // "timed out after 30 s", "ran out of memory", "crashed (Segmentation fault)", "exit status 3" or "ok".
    std::string describe(double limitSeconds) const;
};

// Runs argv[0] (a path, not searched in PATH) with argv. Throws voxlab::Error
// only when the process cannot be started at all.
ChildResult runChild(const std::vector<std::string>& argv, const ChildLimits& limits);

// Landlock write confinement works on this kernel.
bool sandboxAvailable();

// The isolation layers runChild(isolate) gets on this machine, as listed in
// ChildResult::sandbox (found by starting a trivial isolated child once),
// and those it lacks (ChildResult::sandboxMissing).
std::vector<std::string> sandboxLayers();
std::vector<std::string> sandboxMissingLayers();

}  // namespace voxlab
