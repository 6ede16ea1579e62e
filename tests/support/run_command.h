// Test support: run the voxlab binary (or any shell command) and capture
// its exit code, stdout and stderr.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "temp_dir.h"

namespace voxlab::testing {

struct CommandResult {
    int exitCode = -1;
    std::string out, err;
};

inline std::string readFile(const std::string& path) { return readText(path); }

// Runs `command` through the shell with a time limit (seconds).
inline CommandResult runShell(const std::string& command, int timeoutSeconds = 120) {
    static int counter = 0;
    const std::string base = "/tmp/voxlab_cmd_" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    const std::string full = "timeout " + std::to_string(timeoutSeconds) + " " + command + " >" + base +
                             ".out 2>" + base + ".err </dev/null";
    const int status = std::system(full.c_str());
    CommandResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readFile(base + ".out");
    r.err = readFile(base + ".err");
    std::remove((base + ".out").c_str());
    std::remove((base + ".err").c_str());
    return r;
}

inline CommandResult runVoxlab(const std::string& args, int timeoutSeconds = 120) {
    return runShell(std::string(VOXLAB_BINARY) + " " + args, timeoutSeconds);
}

inline int lineCount(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n + (!s.empty() && s.back() != '\n');
}

}  // namespace voxlab::testing
