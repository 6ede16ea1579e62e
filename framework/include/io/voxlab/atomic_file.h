// voxlab: saving files so that a failed save never costs the old file.
//
// Every file voxlab writes (images, scenes, transfer functions, volumes,
// reports) goes through writeFileAtomically():
//   - the bytes go to a temporary file in the same folder (".NAME.XXXXXX"),
//     every write and the close are checked, and the file is flushed to disk;
//   - only then is it renamed over PATH, which the kernel does in one step:
//     a reader sees the old file or the new one, never half of one;
//   - a symbolic link at PATH is replaced, never followed, so a link planted
//     in a folder cannot redirect the write elsewhere;
//   - PATH that is a device, FIFO or other non-regular file (/dev/stdout,
//     /dev/null, /dev/full) is written in place, with every write checked.
// A failure throws voxlab::Error naming the path and the reason ("out.png:
// cannot write: No space left on device"); the temporary file is removed
// and whatever was at PATH before is still there.
#pragma once

#include <string>
#include <string_view>

namespace voxlab {

void writeFileAtomically(const std::string& path, std::string_view bytes);

}  // namespace voxlab
