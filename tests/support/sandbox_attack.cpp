// sandbox_attack: what a hostile stage would try, one attack per run, for
// tests/test_child_process.cpp to mount inside and outside the grader's
// sandbox. Prints one line, "ATTACK: allowed" or "ATTACK: denied (ERRNO)",
// or for the measuring attacks what it got ("memfd: held 512 MiB").
//
//   sandbox_attack keyring | hostname | nice | fifo | kmsg | blockdev | inet
//                  | mount | unshare | clone-newuser | bpf | perf | io_uring
//                  | userfaultfd | ptrace | capabilities
//   sandbox_attack unix PATH          connect to a UNIX socket
//   sandbox_attack env NAME           print $NAME (or "unset")
//   sandbox_attack memfd MIB          hold MIB in a memfd, 16 MiB at a time
//   sandbox_attack children N MIB     N children each touching MIB
//   sandbox_attack write PATH MIB     write MIB into PATH
#include <errno.h>
#include <fcntl.h>
#include <linux/perf_event.h>
#include <sched.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/mount.h>
#include <sys/ptrace.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fstream>
#include <string>
#include <vector>

namespace {

int report(const char* attack, long rc) {
    if (rc >= 0) std::printf("%s: allowed\n", attack);
    else std::printf("%s: denied (%s)\n", attack, strerrorname_np(errno));
    return 0;
}

// Every block device the machine lists, opened for reading and writing.
long openBlockDevice() {
    DIR* dir = opendir("/sys/class/block");
    if (!dir) return errno = ENOENT, -1;
    long rc = -1;
    int lastErrno = ENOENT;
    for (dirent* e; (e = readdir(dir));) {
        if (e->d_name[0] == '.') continue;
        const std::string dev = std::string("/dev/") + e->d_name;
        const int fd = open(dev.c_str(), O_RDWR | O_CLOEXEC);
        if (fd >= 0) {
            std::printf("opened %s\n", dev.c_str());
            close(fd);
            rc = 0;
            break;
        }
        lastErrno = errno;
    }
    closedir(dir);
    if (rc < 0) errno = lastErrno;
    return rc;
}

// "allowed" when any of the permitted, effective, bounding or ambient
// capability sets is not empty.
long capabilities() {
    std::ifstream in("/proc/self/status");
    bool any = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("Cap", 0) != 0 || line.rfind("CapInh", 0) == 0) continue;
        std::printf("%s\n", line.c_str());
        if (std::strtoull(line.substr(line.find(':') + 1).c_str(), nullptr, 16) != 0) any = true;
    }
    if (!any) errno = EPERM;
    return any ? 0 : -1;
}

long connectUnix(const char* path) {
    const int s = socket(AF_UNIX, SOCK_STREAM, 0);
    if (s < 0) return -1;
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path, sizeof addr.sun_path - 1);
    const long rc = connect(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
    if (rc == 0 && write(s, "stolen", 6) < 0) return -1;
    close(s);
    return rc;
}

int memfd(long mib) {
    const int fd = int(syscall(SYS_memfd_create, "hostile", 0));
    if (fd < 0) return report("memfd", -1);
    std::vector<char> chunk(16 << 20, 'x');
    long held = 0;
    while (held < mib && write(fd, chunk.data(), chunk.size()) == ssize_t(chunk.size())) held += 16;
    std::printf("memfd: held %ld MiB\n", held);
    return 0;
}

int children(int count, long mib) {
    for (int i = 0; i < count; ++i)
        if (fork() == 0) {
            char* p = static_cast<char*>(std::malloc(std::size_t(mib) << 20));
            if (!p) _exit(2);
            for (long b = 0; b < (mib << 20); b += 4096) p[b] = 1;
            std::printf("child: touched %ld MiB\n", mib);
            std::fflush(stdout);
            sleep(2);
            _exit(0);
        }
    int done = 0, status = 0;
    while (wait(&status) > 0)
        if (WIFEXITED(status) && WEXITSTATUS(status) == 0) ++done;
    std::printf("children: %d of %d held %ld MiB each\n", done, count, mib);
    return 0;
}

int writeFile(const char* path, long mib) {
    const int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) return report("write", -1);
    signal(SIGXFSZ, SIG_IGN);
    std::vector<char> chunk(1 << 20, 'x');
    long wrote = 0;
    while (wrote < mib && write(fd, chunk.data(), chunk.size()) == ssize_t(chunk.size())) ++wrote;
    std::printf("write: wrote %ld MiB\n", wrote);
    close(fd);
    return 0;
}

long syscallAttack(const std::string& a) {
    if (a == "keyring")
        return syscall(SYS_add_key, "user", "voxlab-hostile-key", "secret", 6, -4 /*KEY_SPEC_USER_KEYRING*/);
    if (a == "hostname") return sethostname("voxlab-hostile", 14);
    if (a == "nice") return setpriority(PRIO_PROCESS, 0, -20);
    if (a == "fifo") {
        sched_param p{};
        p.sched_priority = 1;
        return sched_setscheduler(0, SCHED_FIFO, &p);
    }
    if (a == "kmsg") return open("/dev/kmsg", O_WRONLY | O_CLOEXEC);
    if (a == "blockdev") return openBlockDevice();
    if (a == "inet") return socket(AF_INET, SOCK_STREAM, 0);
    if (a == "mount") return mount("none", "/tmp", "tmpfs", 0, nullptr);
    if (a == "unshare") return unshare(CLONE_NEWUSER);
    if (a == "clone-newuser") {
        const long pid = syscall(SYS_clone, CLONE_NEWUSER | SIGCHLD, nullptr, nullptr, nullptr, 0);
        if (pid == 0) _exit(0);
        if (pid > 0) waitpid(pid_t(pid), nullptr, 0);
        return pid;
    }
    if (a == "bpf") return syscall(SYS_bpf, 0, nullptr, 0);
    if (a == "perf") {
        perf_event_attr attr{};
        attr.size = sizeof attr;
        attr.type = PERF_TYPE_SOFTWARE;
        attr.config = PERF_COUNT_SW_CPU_CLOCK;
        return syscall(SYS_perf_event_open, &attr, 0, -1, -1, 0);
    }
    if (a == "io_uring") {
        char params[120] = {};
        return syscall(SYS_io_uring_setup, 1, params);
    }
    if (a == "userfaultfd") return syscall(SYS_userfaultfd, 0);
    if (a == "ptrace") return ptrace(PTRACE_ATTACH, getppid(), nullptr, nullptr);
    if (a == "capabilities") return capabilities();
    errno = EINVAL;
    return -2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return 2;
    const std::string a = argv[1];
    if (a == "unix" && argc == 3) return report("unix", connectUnix(argv[2]));
    if (a == "env" && argc == 3) {
        const char* v = std::getenv(argv[2]);
        std::printf("env: %s=%s\n", argv[2], v ? v : "unset");
        return 0;
    }
    if (a == "memfd" && argc == 3) return memfd(std::atol(argv[2]));
    if (a == "children" && argc == 4) return children(std::atoi(argv[2]), std::atol(argv[3]));
    if (a == "write" && argc == 4) return writeFile(argv[2], std::atol(argv[3]));
    const long rc = syscallAttack(a);
    if (rc == -2) return 2;
    return report(a.c_str(), rc);
}
