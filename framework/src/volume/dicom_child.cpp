// voxlab: loadDicom — the DICOM loader (dicom_loader.cpp) run in a forked
// child process, so that GDCM failing on a damaged file costs one error
// message, not the program.
//
// Why. Debian's GDCM keeps its assert()s (built without NDEBUG): a file cut
// in the middle of an attribute header makes GDCM call abort() inside
// gdcm::Reader, which no try/catch can turn into an error. Codecs fed
// damaged compressed data may also crash. voxlab promises a one-line error
// for any bad input, so the reading happens in a child:
//
//   parent ── fork ──> child: loadDicomHere(path), then writes the volume
//      |                (or the error message) to a pipe and _exit()s.
//      └── reads the pipe, waitpid()s. A child that died by a signal, or
//          made no progress for kStallSeconds, becomes
//          "PATH: GDCM crashed reading IM0042.dcm (Aborted); is the file damaged?"
//
// The child names the file GDCM is reading in a page shared with the parent
// (detail::dicomReading). It inherits the parent's memory copy-on-write and
// makes no new threads; its stdout and stderr go to /dev/null (GDCM's
// assert message would be a second line); it ends with _exit, so no atexit
// handler or stdio buffer of the parent runs twice. The volume crosses the pipe once (about
// 0.1 s per 100 MiB); the parent re-checks its sizes before allocating.
//
// A damaged length field can make GDCM allocate (and zero) gigabytes for a
// small file (a Pixel Data length of 0xFFFFFFF0 in a 1 KiB file: 4 GiB and
// 7 s). So the child caps its address space (RLIMIT_AS) before each phase at
// what it has mapped plus what the phase needs (detail::dicomMemoryBudget:
// twice the largest file while the attributes are read; the voxels, before
// and after the rescale, and a few slices' worth while the pixels are), and
// std::bad_alloc becomes "GDCM ran out of memory reading FILE (a damaged
// length field?)". Not under AddressSanitizer, which reserves terabytes of
// address space.
//
// VOXLAB_DICOM_IN_PROCESS=1 reads in the calling process instead: for the
// fuzz target (tests/fuzz/fuzz_dicom.cpp), whose coverage and crash reports
// must come from the process libFuzzer watches, and for debuggers.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>

#include "dicom_internal.h"
#include "voxlab/fd_io.h"
#include "voxlab/sanitizer.h"
#include "volume_io_util.h"

namespace voxlab {

namespace {

// No sign of life from the child for this long: it is stuck in GDCM.
constexpr int kStallSeconds = 60;

// Shared between the parent and its child (MAP_SHARED): what GDCM reads now.
struct Progress {
    std::atomic<std::uint64_t> steps{0};
    char file[1024] = {};
};

Progress* g_progress = nullptr;  // set in the child only

constexpr bool kAddressSpaceCapWorks = !kAddressSanitized;  // (sanitizer.h)

// Room for the C++ runtime, GDCM's dictionaries and small buffers.
constexpr std::uint64_t kMemorySlack = std::uint64_t(256) << 20;


bool inProcess() {
    const char* v = std::getenv("VOXLAB_DICOM_IN_PROCESS");
    return v && std::string(v) == "1";
}

// ---- the wire format: 'E' + message, or 'V' + the volume ---------------------------

void putU64(std::string& out, std::uint64_t v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }
void putText(std::string& out, const std::string& text) {
    putU64(out, text.size());
    out += text;
}

// Everything but the voxels, which follow it on the pipe.
std::string volumeHeader(const Volume& v) {
    std::string out = "V";
    for (int a = 0; a < 3; ++a) putU64(out, std::uint64_t(v.dims()[a]));
    putU64(out, std::uint64_t(v.type()));
    for (int a = 0; a < 3; ++a) {
        const double s = v.spacing()[a];
        out.append(reinterpret_cast<const char*>(&s), sizeof s);
    }
    putText(out, v.name());
    putU64(out, v.metadata().size());
    for (const auto& [key, value] : v.metadata()) {
        putText(out, key);
        putText(out, value);
    }
    putU64(out, v.bytes().size());
    return out;
}

// "IM0042.dcm" for ".../IM0042.dcm"; "the series" before any file.
std::string fileName(const std::string& path) {
    const std::size_t slash = path.rfind('/');
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    return name.empty() ? "the series" : name;
}

[[noreturn]] void runChild(const std::string& path, int fd) {
    // A crash ends the child by its signal, whatever handlers the parent
    // installed (libFuzzer's would report the child's crash as its own).
    for (int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) ::signal(sig, SIG_DFL);
    // GDCM's failed assert() prints to stderr before it aborts: the parent
    // says it in one line instead.
    const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
    if (null >= 0) {
        ::dup2(null, 1);
        ::dup2(null, 2);
    }
    std::string message;
    try {
        const Volume v = detail::loadDicomHere(path);
        const std::string header = volumeHeader(v);
        const std::string_view voxels(reinterpret_cast<const char*>(v.bytes().data()), v.bytes().size());
        const bool sent = writeAll(fd, header) == 0 && writeAll(fd, voxels) == 0;
        _exit(sent ? 0 : 3);
    } catch (const Error& e) {
        message = e.what();
    } catch (const std::bad_alloc&) {
        message = path + ": GDCM ran out of memory reading " + fileName(g_progress->file) +
                  " (a damaged length field?)";
    } catch (const std::exception& e) {
        message = path + ": GDCM failed reading " + fileName(g_progress->file) + " (" + e.what() + ")";
    } catch (...) {
        message = path + ": GDCM failed reading " + fileName(g_progress->file);
    }
    for (char& c : message)
        if (c == '\n' || c == '\r') c = ' ';
    _exit(writeAll(fd, "E" + message) == 0 ? 0 : 3);
}

// ---- the parent -------------------------------------------------------------------------

struct Reader {
    int fd;
    pid_t pid;
    const Progress* progress;
    mutable bool stalled = false;

    // Waits until `fd` has data or is closed, while the child makes progress.
    bool waitForData() const {
        std::uint64_t seen = progress->steps.load();
        auto lastChange = std::chrono::steady_clock::now();
        for (;;) {
            pollfd p{fd, POLLIN, 0};
            const int n = ::poll(&p, 1, 1000);
            if (n > 0) return true;
            if (n < 0 && errno != EINTR) return false;
            const std::uint64_t now = progress->steps.load();
            if (now != seen) {
                seen = now;
                lastChange = std::chrono::steady_clock::now();
            } else if (std::chrono::steady_clock::now() - lastChange > std::chrono::seconds(kStallSeconds)) {
                ::kill(pid, SIGKILL);
                stalled = true;
                return false;
            }
        }
    }
    bool read(void* data, std::size_t size) const {
        auto* p = static_cast<char*>(data);
        while (size > 0) {
            if (!waitForData()) return false;
            const ssize_t n = ::read(fd, p, size);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) return false;
            p += n;
            size -= std::size_t(n);
        }
        return true;
    }
    bool u64(std::uint64_t& v) const { return read(&v, sizeof v); }
    bool text(std::string& out) const {
        std::uint64_t n = 0;
        if (!u64(n) || n > (1u << 20)) return false;
        out.resize(std::size_t(n));
        return read(out.data(), out.size());
    }
};

// The child's answer: a volume, or throws its error. Returns false when the
// answer broke off (the child died).
bool readAnswer(const std::string& path, const Reader& in, Volume& volume) {
    char kind = 0;
    if (!in.read(&kind, 1)) return false;
    if (kind == 'E') {
        std::string message;
        for (char c; in.read(&c, 1) && message.size() < 4096;) message += c;
        throw Error(message.empty() ? path + ": the DICOM reader failed" : message);
    }
    std::uint64_t d[3], type = 0, count = 0, size = 0;
    double spacing[3];
    std::string name;
    Volume::Metadata metadata;
    if (kind != 'V' || !in.u64(d[0]) || !in.u64(d[1]) || !in.u64(d[2]) || !in.u64(type) || type > 3 ||
        !in.read(spacing, sizeof spacing) || !in.text(name) || !in.u64(count) || count > 64)
        return false;
    for (std::uint64_t i = 0; i < count; ++i) {
        std::string key, value;
        if (!in.text(key) || !in.text(value)) return false;
        metadata.emplace_back(key, value);
    }
    const auto voxelType = static_cast<VoxelType>(type);
    const std::uint64_t expected =
        detail::checkedVolumeBytes(path, "series", (long long)d[0], (long long)d[1], (long long)d[2], voxelType);
    if (!in.u64(size) || size != expected) return false;
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    if (!in.read(bytes.data(), bytes.size())) return false;
    volume = Volume(glm::ivec3(int(d[0]), int(d[1]), int(d[2])), voxelType,
                    glm::dvec3(spacing[0], spacing[1], spacing[2]), std::move(bytes), name);
    volume.setMetadata(std::move(metadata));
    return true;
}

// "PATH: GDCM crashed reading IM0042.dcm (Aborted); is the file damaged?"
std::string crashMessage(const std::string& path, int status, bool stalled, const Progress& progress) {
    std::string how;
    if (stalled) how = "no progress for " + std::to_string(kStallSeconds) + " s";
    else if (WIFSIGNALED(status)) how = strsignal(WTERMSIG(status));
    else how = "exit status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    return path + ": GDCM crashed reading " + fileName(progress.file) + " (" + how + "); is the file damaged?";
}

}  // namespace

void detail::dicomReading(const std::string& file) {
    if (!g_progress) return;
    const std::size_t n = std::min(file.size(), sizeof g_progress->file - 1);
    std::memcpy(g_progress->file, file.data(), n);
    g_progress->file[n] = '\0';
    g_progress->steps.fetch_add(1);
}

void detail::dicomMemoryBudget(std::uint64_t bytes) {
    if (!g_progress || !kAddressSpaceCapWorks) return;
    std::uint64_t pages = 0;
    std::ifstream statm("/proc/self/statm");  // its first field: the pages mapped now
    if (!(statm >> pages)) return;
    struct rlimit limit;
    if (::getrlimit(RLIMIT_AS, &limit) != 0) return;
    const std::uint64_t mapped = pages * std::uint64_t(::sysconf(_SC_PAGESIZE));
    const std::uint64_t want = mapped + std::min<std::uint64_t>(bytes, std::uint64_t(1) << 46) + kMemorySlack;
    limit.rlim_cur = limit.rlim_max == RLIM_INFINITY ? rlim_t(want) : std::min(rlim_t(want), limit.rlim_max);
    ::setrlimit(RLIMIT_AS, &limit);
}

Volume loadDicom(const std::string& path) {
    if (inProcess()) return detail::loadDicomHere(path);
    void* shared = ::mmap(nullptr, sizeof(Progress), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (shared == MAP_FAILED) throw Error(path + ": cannot start the DICOM reader (" + std::strerror(errno) + ")");
    auto* progress = new (shared) Progress();
    struct Unmap {
        void* p;
        ~Unmap() { ::munmap(p, sizeof(Progress)); }
    } unmap{shared};
    auto cannotStart = [&] { return Error(path + ": cannot start the DICOM reader (" + std::strerror(errno) + ")"); };
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw cannotStart();
    const pid_t pid = ::fork();
    if (pid < 0) {
        const Error error = cannotStart();
        ::close(fds[0]);
        ::close(fds[1]);
        throw error;
    }
    if (pid == 0) {
        ::close(fds[0]);
        g_progress = progress;
        runChild(path, fds[1]);
    }
    ::close(fds[1]);
    Volume volume;
    bool complete = false;
    std::string error;
    const Reader reader{fds[0], pid, progress};
    try {
        complete = readAnswer(path, reader, volume);
    } catch (const Error& e) {
        error = e.what();
    }
    if (!complete && error.empty()) ::kill(pid, SIGKILL);  // a broken answer: make sure it ends
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!error.empty()) throw Error(error);
    if (!complete) throw Error(crashMessage(path, status, reader.stalled, *progress));
    return volume;
}

}  // namespace voxlab
