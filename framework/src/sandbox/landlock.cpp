// voxlab grader internals: Landlock confinement (see landlock.h).
//
// The constants are the kernel's uapi values (include/uapi/linux/landlock.h);
// they are spelled out here because Debian 12's headers (Linux 6.1) stop at
// ABI 3, while the kernels graders run on are often newer.
#include "landlock.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>

#ifndef SYS_landlock_create_ruleset
#define SYS_landlock_create_ruleset 444
#define SYS_landlock_add_rule 445
#define SYS_landlock_restrict_self 446
#endif

namespace voxlab::sandbox {

namespace {

constexpr std::uint64_t kExecute = 1ULL << 0, kWriteFile = 1ULL << 1, kReadFile = 1ULL << 2,
                        kReadDir = 1ULL << 3;
// remove dir/file, make char/dir/reg/sock/fifo/block/sym
constexpr std::uint64_t kChangeTree = (1ULL << 4) | (1ULL << 5) | (1ULL << 6) | (1ULL << 7) | (1ULL << 8) |
                                      (1ULL << 9) | (1ULL << 10) | (1ULL << 11) | (1ULL << 12);
constexpr std::uint64_t kRefer = 1ULL << 13, kTruncate = 1ULL << 14;
constexpr std::uint64_t kBindTcp = 1ULL << 0, kConnectTcp = 1ULL << 1;
constexpr std::uint64_t kScopeAbstractUnix = 1ULL << 0, kScopeSignal = 1ULL << 1;
constexpr unsigned kCreateRulesetVersion = 1u << 0;
constexpr int kRulePathBeneath = 1;

// The kernel's struct landlock_ruleset_attr as of ABI 6; older kernels are
// given the prefix they know (its size tells them which fields exist).
struct RulesetAttr {
    std::uint64_t handledAccessFs;
    std::uint64_t handledAccessNet;
    std::uint64_t scoped;
};

struct __attribute__((packed)) PathBeneathAttr {
    std::uint64_t allowedAccess;
    std::int32_t parentFd;
};

// Rights that make sense on a file (the kernel refuses folder rights there).
constexpr std::uint64_t kFileRights = kExecute | kWriteFile | kReadFile | kTruncate;

// `rights` beneath `path` (a folder), or those of them that make sense on
// a file; `folderRights` instead when `path` is a folder and they are given.
bool allow(int ruleset, const char* path, std::uint64_t rights, std::uint64_t folderRights = ~0ULL) {
    const int fd = open(path, O_PATH | O_CLOEXEC);
    if (fd < 0) return true;  // a path that is not there needs no rule
    struct stat st;
    if (fstat(fd, &st) != 0) {
        close(fd);
        return false;
    }
    PathBeneathAttr rule;
    std::memset(&rule, 0, sizeof rule);
    rule.allowedAccess = S_ISDIR(st.st_mode) ? (rights & folderRights) : (rights & kFileRights);
    rule.parentFd = fd;
    const bool ok = rule.allowedAccess == 0 ||
                    syscall(SYS_landlock_add_rule, ruleset, kRulePathBeneath, &rule, 0) == 0;
    close(fd);
    return ok;
}

}  // namespace

std::vector<std::string> deviceFiles() {
    std::vector<std::string> files;
    for (const char* d : {"/dev/null", "/dev/zero", "/dev/random", "/dev/urandom"})
        if (access(d, F_OK) == 0) files.push_back(d);
    std::error_code ec;
    if (std::filesystem::is_directory("/dev/dri", ec)) files.push_back("/dev/dri");
    for (const char* folder : {"/dev/dri", "/dev"})
        for (const auto& e : std::filesystem::directory_iterator(folder, ec)) {
            const std::string name = e.path().filename().string();
            if (name.rfind("renderD", 0) == 0 || name.rfind("nvidia", 0) == 0) files.push_back(e.path().string());
        }
    return files;
}

int landlockAbi() {
    const long abi = syscall(SYS_landlock_create_ruleset, nullptr, 0, kCreateRulesetVersion);
    return abi < 0 ? 0 : int(abi);
}

unsigned restrictSelf(const std::vector<const char*>& readable, const std::vector<const char*>& writable,
                      const std::vector<const char*>& devices, bool confineReads) {
    const int abi = landlockAbi();
    if (abi < 1) return 0;
    const std::uint64_t readRights = kExecute | kReadFile | kReadDir;
    std::uint64_t writeRights = kWriteFile | kChangeTree;
    if (abi >= 2) writeRights |= kRefer;
    if (abi >= 3) writeRights |= kTruncate;
    RulesetAttr attr;
    std::memset(&attr, 0, sizeof attr);
    attr.handledAccessFs = writeRights | (confineReads ? readRights : 0);
    std::size_t size = sizeof(std::uint64_t);
    unsigned layers = kLandlockWrites | (confineReads ? unsigned(kLandlockReads) : 0u);
    if (abi >= 4) {
        attr.handledAccessNet = kBindTcp | kConnectTcp;  // and no rule grants them back
        size = 2 * sizeof(std::uint64_t);
        layers |= kLandlockNetwork;
    }
    if (abi >= 6) {
        attr.scoped = kScopeAbstractUnix | kScopeSignal;
        size = sizeof attr;
        layers |= kLandlockScopes;
    }
    const int ruleset = int(syscall(SYS_landlock_create_ruleset, &attr, size, 0));
    if (ruleset < 0) return 0;
    // A rule may only grant rights the ruleset handles.
    const std::uint64_t handled = attr.handledAccessFs;
    bool ok = true;
    for (const char* path : writable) ok = ok && allow(ruleset, path, handled);
    if (confineReads)
        for (const char* path : readable) ok = ok && allow(ruleset, path, readRights);
    // Device files, each by name: reading and writing (a folder among them,
    // /dev/dri, only listed). /dev itself is not listable.
    for (const char* device : devices)
        ok = ok && allow(ruleset, device, (kWriteFile | kReadFile | kReadDir) & handled, kReadDir);
    if (ok && prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) == 0 && syscall(SYS_landlock_restrict_self, ruleset, 0) == 0) {
        close(ruleset);
        return layers;
    }
    close(ruleset);
    return 0;
}

}  // namespace voxlab::sandbox
