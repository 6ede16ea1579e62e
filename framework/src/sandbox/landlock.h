// voxlab grader internals: Landlock confinement of a child process.
//
// Landlock (Documentation/userspace-api/landlock.rst, Linux 5.13+) lets an
// unprivileged process restrict itself: it lists the access rights it wants
// the kernel to police ("handled"), grants some of them back beneath chosen
// files and folders, then restricts itself. The restriction is inherited
// across fork and exec and cannot be undone. Each ABI version adds rights:
//   1  file system (read, write, make, remove, execute)
//   2  renaming or linking across folders ("refer")
//   3  truncating
//   4  TCP bind and connect (handled_access_net)
//   6  scopes: signals and abstract UNIX sockets stay inside the sandbox
// A right this kernel does not know is left out, so the same code runs
// confined as far as the kernel allows on any Linux.
#pragma once

#include <string>
#include <vector>

namespace voxlab::sandbox {

// Which layers restrictSelf() put in force (a bit mask).
enum LandlockLayers : unsigned {
    kLandlockWrites = 1u << 0,  // writes only beneath the writable paths (and to device files)
    kLandlockReads = 1u << 1,   // reads and execution only beneath the readable paths
    kLandlockNetwork = 1u << 2, // no TCP bind or connect
    kLandlockScopes = 1u << 3,  // no signals or abstract sockets to processes outside
};

// The ABI version the kernel offers; 0 when Landlock is unavailable.
int landlockAbi();

// The device files a sandboxed process may open, for reading and writing:
// /dev/null, zero, random and urandom, and a GPU's render nodes
// (/dev/dri/renderD*, /dev/nvidia*) with /dev/dri listable. No block device,
// no terminal, no /dev/kmsg. Found on disk (call it before fork).
std::vector<std::string> deviceFiles();

// Restricts the calling process. `readable`, `writable` and `devices`
// (deviceFiles()) are NUL-terminated paths prepared before fork; when
// `confineReads` is false reading stays allowed everywhere. Only
// async-signal-safe calls: it runs between fork and exec. Returns the
// layers in force (0 when Landlock is unavailable).
unsigned restrictSelf(const std::vector<const char*>& readable, const std::vector<const char*>& writable,
                      const std::vector<const char*>& devices, bool confineReads);

}  // namespace voxlab::sandbox
