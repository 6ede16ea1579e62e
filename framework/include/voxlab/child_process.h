// voxlab: running untrusted work in a child process with limits.
//
// The grader runs each submission's stage in its own process: a shader that
// loops forever, a crash or a runaway allocation then costs that stage only.
// runChild() starts a program with a wall-clock limit, an address-space cap
// and a file-size cap, and collects what it prints.
//
// With `isolate`, the child is also boxed in, with every layer this machine
// offers (ChildResult::sandbox lists the ones in force):
//   - its own session and process group, and new PID, network and IPC
//     namespaces (as root, or through a user namespace where unprivileged
//     ones are allowed): the child is process 1 of its namespace, so when it
//     ends, or is killed at the time limit, the kernel ends everything it
//     started, also children that called setsid(); it cannot name, let alone
//     signal, any process outside; it has no network, not even loopback;
//   - a process-count limit: a pids cgroup where one can be made (root), else
//     RLIMIT_NPROC (which the kernel does not apply to root);
//   - Landlock (Linux 5.13+): reads confined to `readable` plus the system
//     folders a program needs (/usr, /lib, /dev, /proc/self, /sys, ...),
//     writes to `writable` (empty: nowhere but device files like /dev/null);
//     from Landlock ABI 4 no TCP connect or bind, from ABI 6 no signals to
//     and no abstract UNIX sockets of processes outside the sandbox.
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

struct ChildLimits {
    double seconds = 60.0;             // wall clock; then everything it started is killed
    std::size_t memoryBytes = 0;       // RLIMIT_AS; 0 leaves it as it is (also under ASan)
    std::size_t fileBytes = 0;         // RLIMIT_FSIZE (largest file it may write); 0: unchanged
    std::size_t outputBytes = 1 << 20; // what is kept of its stdout + stderr
    std::size_t resultsBytes = 0;      // > 0: fd 3 is the results channel (see above)
    std::string workingDir;            // empty: the parent's
    bool isolate = false;              // namespaces, process limit, Landlock reads (see above)
    int maxProcesses = 64;             // with isolate: processes and threads it may have at once
    std::vector<std::string> readable; // with isolate: folders or files it may read
    std::vector<std::string> writable; // folders it may write (with isolate, or when non-empty)
    std::map<std::string, std::string> environment;  // added to (or replacing in) the parent's
};

struct ChildResult {
    int exitCode = -1;     // when it exited normally
    int signal = 0;        // when a signal ended it (after a timeout: SIGKILL)
    bool timedOut = false;
    bool sandboxed = false;  // Landlock confinement was in force
    std::vector<std::string> sandbox;  // the layers in force ("pid namespace", "landlock reads", ...)
    double seconds = 0.0;
    std::string output;    // stdout and stderr, interleaved, possibly truncated
    std::string results;   // what it wrote to fd 3 (resultsBytes > 0)
    bool resultsTruncated = false;

    bool succeeded() const { return !timedOut && signal == 0 && exitCode == 0; }
    // "timed out after 30 s", "crashed (Segmentation fault)", "exit status 3" or "ok".
    std::string describe(double limitSeconds) const;
};

// Runs argv[0] (a path, not searched in PATH) with argv. Throws voxlab::Error
// only when the process cannot be started at all.
ChildResult runChild(const std::vector<std::string>& argv, const ChildLimits& limits);

// Landlock write confinement works on this kernel.
bool sandboxAvailable();

// The isolation layers runChild(isolate) gets on this machine, as listed in
// ChildResult::sandbox (found by starting a trivial isolated child once).
std::vector<std::string> sandboxLayers();

}  // namespace voxlab
