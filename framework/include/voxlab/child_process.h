// voxlab: running untrusted work in a child process with limits.
//
// The grader runs each submission's stage in its own process: a shader that
// loops forever, a crash or a runaway allocation then costs that stage only.
// runChild() starts a program with a wall-clock limit, an address-space cap
// and a file-size cap, in its own process group (so that a timeout kills
// everything it started), and collects what it prints.
//
// Where the kernel offers Landlock (Linux 5.13 and later), the child may
// also be confined so that it can write only below the folders listed in
// `writable` (and to device files, which GPU drivers need); reading stays
// allowed everywhere. sandboxAvailable() says whether that works here.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace voxlab {

struct ChildLimits {
    double seconds = 60.0;             // wall clock; then the process group is killed
    std::size_t memoryBytes = 0;       // RLIMIT_AS; 0 leaves it as it is
    std::size_t fileBytes = 0;         // RLIMIT_FSIZE (largest file it may write); 0: unchanged
    std::size_t outputBytes = 1 << 20; // what is kept of its stdout + stderr
    std::string workingDir;            // empty: the parent's
    std::vector<std::string> writable; // non-empty: confine writes to these folders (Landlock)
    std::map<std::string, std::string> environment;  // added to (or replacing in) the parent's
};

struct ChildResult {
    int exitCode = -1;     // when it exited normally
    int signal = 0;        // when a signal ended it (after a timeout: SIGKILL)
    bool timedOut = false;
    bool sandboxed = false;  // the Landlock confinement was in force
    double seconds = 0.0;
    std::string output;    // stdout and stderr, interleaved, possibly truncated

    bool succeeded() const { return !timedOut && signal == 0 && exitCode == 0; }
    // "timed out after 30 s", "crashed (Segmentation fault)", "exit status 3" or "ok".
    std::string describe(double limitSeconds) const;
};

// Runs argv[0] (a path, not searched in PATH) with argv. Throws voxlab::Error
// only when the process cannot be started at all.
ChildResult runChild(const std::vector<std::string>& argv, const ChildLimits& limits);

bool sandboxAvailable();

}  // namespace voxlab
