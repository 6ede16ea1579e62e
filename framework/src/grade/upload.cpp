// voxlab: copying a student's upload once into a folder the grader owns,
// and unpacking zips (see upload.h).
#include "voxlab/upload.h"

#include <archive.h>
#include <archive_entry.h>
#include <dirent.h>
#include <fcntl.h>
#include <locale.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "voxlab/assignment.h"
#include "voxlab/error.h"
#include "voxlab/grading.h"
#include "voxlab/untrusted_text.h"

namespace voxlab {

namespace fs = std::filesystem;

namespace {

// Thrown inside this file when the whole upload is refused.
struct Refused {
    std::string reason;
};

// A descriptor closed when it goes out of scope.
class Fd {
public:
    explicit Fd(int fd = -1) : fd_(fd) {}
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    ~Fd() {
        if (fd_ >= 0) close(fd_);
    }
    int get() const { return fd_; }

private:
    int fd_;
};

// "16 MiB", "2.9 MiB", "4 KiB", "5000 bytes".
std::string sizeText(std::uintmax_t bytes) {
    constexpr std::uintmax_t kKiB = 1024, kMiB = kKiB * kKiB;
    if (bytes >= kMiB && bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
    if (bytes >= kMiB) {
        char text[32];
        std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(kMiB));
        return text;
    }
    if (bytes >= kKiB && bytes % kKiB == 0) return std::to_string(bytes / kKiB) + " KiB";
    return std::to_string(bytes) + " bytes";
}

// One part of a path, as the copy names it: valid UTF-8 without control
// characters. "" for a part that is not copied at all (dot-files,
// __MACOSX); "." and ".." never reach here.
std::string partName(const std::string& raw) {
    if (raw.empty() || raw[0] == '.' || raw == "__MACOSX") return "";
    std::string name = safeText(raw, 200);
    for (char& c : name)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '_';
    return name;
}

std::string joined(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& p : parts) out += (out.empty() ? "" : "/") + p;
    return out;
}

// The copy being made: counts entries and bytes against the limits and
// writes files under its root, which only the grader writes to.
class Snapshot {
public:
    Snapshot(const std::string& root, const UploadLimits& limits) : root_(root), limits_(limits) {
        if (mkdir(root.c_str(), 0700) != 0)
            throw Error(safeText(root) + ": cannot create the upload's copy: " + std::strerror(errno));
    }
    const UploadLimits& limits() const { return limits_; }
    std::vector<std::string>& leftOut() { return leftOut_; }
    void leaveOut(const std::vector<std::string>& parts, const std::string& why) {
        leftOut_.push_back(joined(parts) + " (" + why + ")");
    }
    void countEntry() {
        if (++entries_ > limits_.maxEntries)
            throw Refused{"the upload holds more than " + std::to_string(limits_.maxEntries) +
                          " files and folders (the limit)"};
    }
    void folder(const std::vector<std::string>& parts) {
        std::error_code ec;
        fs::create_directories(root_ / joined(parts), ec);
        if (ec) throw Refused{"cannot copy " + joined(parts) + "/: " + ec.message()};
    }
    std::uintmax_t bytes() const { return bytes_; }
    // Opens a new file for `parts`; -1 (and left out) when the name is taken.
    int create(const std::vector<std::string>& parts) {
        folder(std::vector<std::string>(parts.begin(), parts.end() - 1));
        const int fd = open((root_ / joined(parts)).c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
        if (fd < 0 && errno == EEXIST) leaveOut(parts, "a second file of that name");
        else if (fd < 0) throw Refused{"cannot copy " + joined(parts) + ": " + std::strerror(errno)};
        return fd;
    }
    // Writes one block of a file; throws when the upload's total is over its cap.
    void write(int fd, const char* data, std::size_t size, const std::vector<std::string>& parts) {
        bytes_ += size;
        if (bytes_ > limits_.maxTotalBytes)
            throw Refused{"the upload holds more than " + sizeText(limits_.maxTotalBytes) + " (the limit)"};
        for (std::size_t done = 0; done < size;) {
            const ssize_t n = ::write(fd, data + done, size - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) throw Refused{"cannot copy " + joined(parts) + ": " + std::strerror(errno)};
            done += std::size_t(n);
        }
    }
    void remove(const std::vector<std::string>& parts) {
        std::error_code ec;
        fs::remove(root_ / joined(parts), ec);
    }

private:
    fs::path root_;
    UploadLimits limits_;
    std::vector<std::string> leftOut_;
    std::size_t entries_ = 0;
    std::uintmax_t bytes_ = 0;
};

// Copies the regular file open at `fd` (its size from fstat) into the snapshot.
void copyFile(int fd, std::uintmax_t size, const std::vector<std::string>& parts, Snapshot& snap) {
    if (size > snap.limits().maxFileBytes) {
        snap.leaveOut(parts, sizeText(size) + ", over the " + sizeText(snap.limits().maxFileBytes) + " a file");
        return;
    }
    const Fd out(snap.create(parts));
    if (out.get() < 0) return;
    std::vector<char> buffer(1 << 16);
    std::uintmax_t copied = 0;
    for (ssize_t n; (n = read(fd, buffer.data(), buffer.size())) != 0;) {
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw Refused{"cannot read " + joined(parts) + ": " + std::strerror(errno)};
        copied += std::uintmax_t(n);
        if (copied > snap.limits().maxFileBytes) {  // it grew while being read
            snap.remove(parts);
            snap.leaveOut(parts, "over the " + sizeText(snap.limits().maxFileBytes) + " a file");
            return;
        }
        snap.write(out.get(), buffer.data(), std::size_t(n), parts);
    }
}

// The names in the folder open at `dirFd`, sorted, without "." and "..".
std::vector<std::string> folderNames(int dirFd) {
    std::vector<std::string> names;
    const int fd = dup(dirFd);
    DIR* dir = fd >= 0 ? fdopendir(fd) : nullptr;
    if (!dir) {
        if (fd >= 0) close(fd);
        throw Refused{std::string("cannot list a folder of the upload: ") + std::strerror(errno)};
    }
    rewinddir(dir);
    while (const dirent* e = readdir(dir))
        if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0) names.push_back(e->d_name);
    closedir(dir);
    std::sort(names.begin(), names.end());
    return names;
}

// Copies the folder open at `dirFd` (at `parts` in the copy), entry by
// entry, each opened without following links and checked on its descriptor.
void copyFolder(int dirFd, const std::vector<std::string>& parts, Snapshot& snap) {
    for (const std::string& raw : folderNames(dirFd)) {
        const std::string name = partName(raw);
        if (name.empty()) continue;
        snap.countEntry();
        std::vector<std::string> path = parts;
        path.push_back(name);
        struct stat st;
        if (fstatat(dirFd, raw.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) {
            snap.leaveOut(path, "cannot be read");
            continue;
        }
        if (S_ISLNK(st.st_mode) || !(S_ISREG(st.st_mode) || S_ISDIR(st.st_mode))) {
            snap.leaveOut(path, S_ISLNK(st.st_mode) ? "a link" : "not a regular file");
            continue;
        }
        const Fd fd(openat(dirFd, raw.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
        if (fd.get() < 0 || fstat(fd.get(), &st) != 0) {
            snap.leaveOut(path, errno == ELOOP ? "a link" : "cannot be read");
            continue;
        }
        if (S_ISDIR(st.st_mode) && int(path.size()) > snap.limits().maxDepth) {
            snap.leaveOut(path, "deeper than " + std::to_string(snap.limits().maxDepth) + " folders");
        } else if (S_ISDIR(st.st_mode)) {
            snap.folder(path);
            copyFolder(fd.get(), path, snap);
        } else if (S_ISREG(st.st_mode)) {
            copyFile(fd.get(), std::uintmax_t(st.st_size), path, snap);
        } else {
            snap.leaveOut(path, "not a regular file");  // it changed between the two looks
        }
    }
}

bool isZipName(const std::string& name) {
    if (name.size() < 5) return false;
    std::string ext = name.substr(name.size() - 4);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".zip";
}

// The one .zip file a folder holds besides dot-files, if that is all it holds.
std::string loneZip(int dirFd) {
    std::vector<std::string> visible;
    for (const std::string& name : folderNames(dirFd))
        if (name[0] != '.') visible.push_back(name);
    struct stat st;
    if (visible.size() != 1 || !isZipName(visible[0]) ||
        fstatat(dirFd, visible[0].c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode))
        return "";
    return visible[0];
}

}  // namespace

// ---------------------------------------------------------------------------
// Zips, through libarchive: entries are read one by one and every file is
// written here, by Snapshot, never by libarchive's own extraction.

namespace {

std::string archiveError(archive* a) {
    const char* e = archive_error_string(a);
    return safeText(e ? e : "unknown error", 300);
}

// The parts of a zip entry's name ("\" counts as "/"); refuses an absolute
// name and one that climbs out with "..".
std::vector<std::string> entryParts(std::string name) {
    std::replace(name.begin(), name.end(), '\\', '/');
    const std::string shown = terminalLine(name, 200);
    if (name.empty()) throw Refused{"the zip has an entry without a name"};
    if (name[0] == '/' || (name.size() >= 2 && std::isalpha(static_cast<unsigned char>(name[0])) && name[1] == ':'))
        throw Refused{"the zip's entry '" + shown + "' is an absolute path: refused"};
    std::vector<std::string> parts;
    for (std::size_t start = 0; start <= name.size();) {
        const std::size_t end = std::min(name.find('/', start), name.size());
        const std::string part = name.substr(start, end - start);
        if (part == "..") throw Refused{"the zip's entry '" + shown + "' climbs out of its folder with '..': refused"};
        if (!part.empty() && part != ".") parts.push_back(part);
        start = end + 1;
    }
    return parts;
}

// Refuses an entry that is anything but a regular file or a folder.
void requirePlainEntry(archive_entry* entry, const std::string& shown) {
    const mode_t type = archive_entry_filetype(entry);
    if (type == AE_IFLNK || archive_entry_symlink(entry))
        throw Refused{"the zip's entry '" + shown + "' is a link: refused"};
    if (archive_entry_hardlink(entry)) throw Refused{"the zip's entry '" + shown + "' is a hard link: refused"};
    if (type != AE_IFREG && type != AE_IFDIR)
        throw Refused{"the zip's entry '" + shown + "' is not a regular file or a folder: refused"};
}

// Writes the current entry's data into the snapshot, within the caps.
void unpackFile(archive* a, archive_entry* entry, const std::vector<std::string>& path, std::uintmax_t zipBytes,
                Snapshot& snap) {
    const UploadLimits& limits = snap.limits();
    const std::string cap = "over the " + sizeText(limits.maxFileBytes) + " a file";
    if (archive_entry_size_is_set(entry) && std::uintmax_t(archive_entry_size(entry)) > limits.maxFileBytes) {
        snap.leaveOut(path, sizeText(std::uintmax_t(archive_entry_size(entry))) + ", " + cap);
        return;
    }
    const std::uintmax_t allowed =
        std::max(limits.zipRatioFloor, std::uintmax_t(limits.maxZipRatio * double(zipBytes)));
    const Fd out(snap.create(path));
    if (out.get() < 0) return;
    std::vector<char> buffer(1 << 16);
    std::uintmax_t written = 0;
    for (la_ssize_t n; (n = archive_read_data(a, buffer.data(), buffer.size())) != 0;) {
        if (n < 0) throw Refused{"the zip cannot be unpacked (" + joined(path) + "): " + archiveError(a)};
        written += std::uintmax_t(n);
        if (written > limits.maxFileBytes) {
            snap.remove(path);
            snap.leaveOut(path, cap);
            return;
        }
        if (snap.bytes() + std::uintmax_t(n) > allowed) {
            char ratio[32];
            std::snprintf(ratio, sizeof ratio, "%g", limits.maxZipRatio);
            throw Refused{"the zip unpacks to more than " + std::string(ratio) + " times its own size (" +
                          sizeText(zipBytes) + "): a zip bomb? refused"};
        }
        snap.write(out.get(), buffer.data(), std::size_t(n), path);
    }
}

// One entry: refused, left out, or written.
void unpackEntry(archive* a, archive_entry* entry, std::uintmax_t zipBytes, Snapshot& snap) {
    const char* raw = archive_entry_pathname(entry);
    if (!raw) raw = archive_entry_pathname_utf8(entry);
    if (!raw) throw Refused{"the zip has an entry whose name cannot be read: " + archiveError(a)};
    const std::vector<std::string> parts = entryParts(raw);
    requirePlainEntry(entry, terminalLine(raw ? raw : "", 200));
    std::vector<std::string> path;
    for (const std::string& p : parts) {
        path.push_back(partName(p));
        if (path.back().empty()) return;  // a dot-file, __MACOSX: not copied
    }
    if (path.empty()) return;
    const bool isFolder = archive_entry_filetype(entry) == AE_IFDIR;
    if (int(path.size()) - (isFolder ? 0 : 1) > snap.limits().maxDepth) {
        snap.leaveOut(path, "deeper than " + std::to_string(snap.limits().maxDepth) + " folders");
    } else if (isFolder) {
        snap.folder(path);
    } else {
        unpackFile(a, entry, path, zipBytes, snap);
    }
}

struct ArchiveReader {
    void operator()(archive* a) const { archive_read_free(a); }
};

// libarchive converts a zip entry's UTF-8 name to the locale's character
// set, and in the "C" locale of a program that never calls setlocale() that
// fails for every name beyond ASCII ("café/"). A UTF-8 locale for this
// thread, while a zip is read, keeps names as they are (safeText makes the
// rest valid); without one, such names stay unreadable.
class Utf8Names {
public:
    Utf8Names() {
        for (const char* name : {"C.UTF-8", "C.utf8", "en_US.UTF-8"})
            if ((locale_ = newlocale(LC_CTYPE_MASK, name, locale_t(nullptr)))) break;
        if (locale_) previous_ = uselocale(locale_);
    }
    Utf8Names(const Utf8Names&) = delete;
    Utf8Names& operator=(const Utf8Names&) = delete;
    ~Utf8Names() {
        if (!locale_) return;
        uselocale(previous_);
        freelocale(locale_);
    }

private:
    locale_t locale_ = locale_t(nullptr), previous_ = locale_t(nullptr);
};

// Unpacks the zip open at `fd` into the snapshot.
void unpackZipFd(int fd, std::uintmax_t zipBytes, Snapshot& snap) {
    const Utf8Names names;
    const std::unique_ptr<archive, ArchiveReader> a(archive_read_new());
    if (!a) throw Error("libarchive: out of memory");
    archive_read_support_format_zip(a.get());
    if (archive_read_open_fd(a.get(), fd, 1 << 16) != ARCHIVE_OK)
        throw Refused{"the upload is not a zip that can be read: " + archiveError(a.get())};
    archive_entry* entry = nullptr;
    for (int r; (r = archive_read_next_header(a.get(), &entry)) != ARCHIVE_EOF;) {
        if (r < ARCHIVE_WARN) throw Refused{"the zip cannot be unpacked: " + archiveError(a.get())};
        snap.countEntry();
        unpackEntry(a.get(), entry, zipBytes, snap);
    }
}

// Copies or unpacks the upload open at `top` into the snapshot.
void copyOpenUpload(int top, const std::string& upload, Snapshot& snap) {
    struct stat st;
    if (fstat(top, &st) != 0) throw Refused{std::string("the upload cannot be read: ") + std::strerror(errno)};
    if (S_ISREG(st.st_mode) && isZipName(upload)) return unpackZipFd(top, std::uintmax_t(st.st_size), snap);
    if (!S_ISDIR(st.st_mode)) throw Refused{"the upload is neither a folder nor a .zip file"};
    const std::string zip = loneZip(top);
    if (zip.empty()) return copyFolder(top, {}, snap);
    const Fd fd(openat(top, zip.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
    if (fd.get() < 0 || fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode))
        throw Refused{"the upload's zip " + terminalLine(zip, 200) + " cannot be read"};
    unpackZipFd(fd.get(), std::uintmax_t(st.st_size), snap);
}

}  // namespace

UploadCopy copyUpload(const std::string& upload, const std::string& into, const UploadLimits& limits) {
    UploadCopy copy;
    // The path itself may be a link (the instructor named it); nothing inside it is followed.
    const Fd top(open(upload.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
    if (top.get() < 0) {
        copy.problem = std::string("the upload cannot be read: ") + std::strerror(errno);
        return copy;
    }
    Snapshot snap(into, limits);
    try {
        copyOpenUpload(top.get(), upload, snap);
        copy.leftOut = snap.leftOut();
    } catch (const Refused& r) {
        copy.problem = r.reason;
        std::error_code ec;
        fs::remove_all(into, ec);
        fs::create_directory(into, ec);
    }
    return copy;
}

UploadCopy unpackZip(const std::string& zip, const std::string& into, const UploadLimits& limits) {
    if (!isZipName(zip)) return {"not a .zip file: " + terminalLine(zip, 200), {}};
    return copyUpload(zip, into, limits);
}

// ---------------------------------------------------------------------------
// From an upload to a submission ready for grading.

namespace {

// "a, b, c and 4 more"
std::string someOf(const std::vector<std::string>& items, std::size_t shown = 5) {
    std::string out;
    for (std::size_t i = 0; i < items.size() && i < shown; ++i) out += (i ? ", " : "") + items[i];
    if (items.size() > shown) out += " and " + std::to_string(items.size() - shown) + " more";
    return out;
}

// The stages an upload is shaped for: those asked for that have a manifest.
std::vector<std::string> stagesToFind(const GraderOptions& options) {
    std::vector<std::string> stages;
    for (const std::string& s : options.stages.empty() ? gradedStages(options.referenceRoot) : options.stages)
        if (fs::exists(fs::path(options.referenceRoot) / s / "grading.json")) stages.push_back(s);
    return stages;
}

// Why a shaped upload cannot be graded: it holds no stage folder at all.
std::string whyUngradable(const std::string& root, const std::string& copy, const GraderOptions& options,
                          const std::vector<std::string>& stages) {
    std::error_code ec;
    for (const std::string& s : stages)
        if (fs::is_directory(fs::path(root) / s, ec)) return "";
    if (stages.empty()) return "";  // an unknown stage: the grader reports it
    std::vector<std::string> held, folders, files;
    for (const auto& entry : fs::directory_iterator(copy, ec)) held.push_back(entry.path().filename().string());
    std::sort(held.begin(), held.end());
    if (held.empty()) return "the upload is empty (dot-files, links and special files are not graded)";
    for (const std::string& s : stages) {
        folders.push_back(s + "/");
        for (const std::string& f : loadStageManifest(options.referenceRoot, s).files) files.push_back(f);
    }
    return "no stage folder (" + someOf(folders, 3) + ") and no stage file (" + someOf(files, 3) +
           ") anywhere in the upload, which holds " + someOf(held);
}

}  // namespace

Submission prepareSubmission(const std::string& name, const std::string& upload, const std::string& reportDir,
                             const std::string& snapshot, const GraderOptions& options, const UploadLimits& limits) {
    Submission s;
    s.name = safeText(name, kMaxNameBytes);
    s.upload = safeText(upload, 4 * kMaxNameBytes);
    s.reportDir = reportDir;
    s.folder = snapshot;
    try {
        const UploadCopy copy = copyUpload(upload, snapshot, limits);
        s.problem = copy.problem;
        if (!s.problem.empty()) return s;
        const std::vector<std::string> stages = stagesToFind(options);
        std::string note;
        s.folder = submissionRoot(snapshot, options.referenceRoot, stages, snapshot + ".placed", &note);
        if (!copy.leftOut.empty())
            note += (note.empty() ? "" : "; ") + std::string("left out of the upload: ") + someOf(copy.leftOut);
        s.layoutNote = safeText(note);
        s.problem = whyUngradable(s.folder, snapshot, options, stages);
    } catch (const std::exception& e) {
        s.problem = safeText(std::string("the upload cannot be prepared for grading: ") + e.what());
    }
    return s;
}

}  // namespace voxlab
