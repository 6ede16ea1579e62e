// voxlab grader internals: a system-call allow-list for grader children.
//
// Every child the grader starts on a submission's behalf (the C++ compiler,
// the worker that renders, the stage host that runs a C++ stage) runs under
// a seccomp filter that allows only the system calls those programs need
// and fails every other with EPERM: default deny. What is left out on
// purpose, and why, is listed in syscall_filter.cpp beside the list; the
// threat model in docs/grading.md names what each denial stops.
//
// The filter is built once per process with libseccomp (never hand-written
// BPF) and exported as a BPF program before fork, so that the child only
// has to hand the kernel a ready program between fork and exec, which is
// async-signal-safe. A filter is inherited across fork and exec and cannot
// be removed.
#pragma once

#include <string>

namespace voxlab::sandbox {

// The allow-list as a BPF program, built on first use. `error()` says why
// there is none (libseccomp failed); then the child runs without the layer
// and the report says so.
class SyscallFilter {
public:
    static const SyscallFilter& instance();

    bool ready() const { return !program_.empty(); }
    const std::string& error() const { return error_; }
    // Loads the filter into the calling process (async-signal-safe; needs
    // PR_SET_NO_NEW_PRIVS). Returns false when the kernel refused it.
    bool load() const;

private:
    SyscallFilter();
    std::string program_;  // struct sock_filter[], as libseccomp exported it
    std::string error_;
};

}  // namespace voxlab::sandbox
