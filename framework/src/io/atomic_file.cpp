// voxlab: atomic, checked file writes (see atomic_file.h).
//
// The classic recipe: write a temporary file in the same folder (rename is
// atomic only within one file system), fsync it, rename it over the target.
// POSIX rename(2) replaces a symbolic link rather than the file it points
// to, which is what keeps a planted link from redirecting a save.
#include "voxlab/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "voxlab/error.h"
#include "voxlab/fd_io.h"

namespace voxlab {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, int err) {
    throw Error(path + ": cannot " + what + ": " + std::strerror(err));
}

void writeInPlace(const std::string& path, std::string_view bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) fail(path, "open for writing", errno);
    const int err = writeAll(fd, bytes);
    if (::close(fd) != 0 && err == 0) fail(path, "write", errno);
    if (err) fail(path, "write", err);
}

}  // namespace

void writeFileAtomically(const std::string& path, std::string_view bytes) {
    if (path.empty()) throw Error("cannot write a file with an empty name");
    struct stat st {};
    if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode)) {
        if (S_ISDIR(st.st_mode)) throw Error(path + ": cannot write: it is a folder");
        writeInPlace(path, bytes);  // a device or FIFO: there is nothing to replace
        return;
    }
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::string temp = (folder / ("." + target.filename().string() + ".XXXXXX")).string();
    const int fd = ::mkstemp(temp.data());
    if (fd < 0) fail(path, "write (creating a temporary file in " + folder.string() + ")", errno);
    int err = writeAll(fd, bytes);
    // mkstemp makes 0600 files; a saved file is readable by all (umask(2)
    // cannot be read without changing it, which would race other threads).
    if (!err && ::fchmod(fd, 0644) != 0) err = errno;
    if (!err && ::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) err = errno;
    if (::close(fd) != 0 && !err) err = errno;
    if (!err && ::rename(temp.c_str(), path.c_str()) != 0) err = errno;
    if (err) {
        ::unlink(temp.c_str());
        fail(path, "write", err);
    }
}

}  // namespace voxlab
