// voxlab: whole reads and writes on file descriptors, retrying when a
// signal interrupts them and continuing after short transfers (pipes,
// sockets and full disks transfer less than asked for).
#pragma once

#include <cstddef>
#include <string_view>

namespace voxlab {

// Writes all of `bytes` to `fd`. Returns 0, or the errno of the failure
// (ENOSPC when a write makes no progress).
int writeAll(int fd, std::string_view bytes);

// Reads exactly `size` bytes into `data`; false at end of file or on error.
bool readAll(int fd, void* data, std::size_t size);

}  // namespace voxlab
