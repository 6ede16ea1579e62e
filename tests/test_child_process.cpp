// Child processes with limits (voxlab/child_process.h): what the grader
// relies on to survive a submission that hangs, crashes, eats memory or
// writes where it should not.
#include <gtest/gtest.h>

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <iostream>
#include <thread>

#include "voxlab/child_process.h"
#include "voxlab/error.h"
#include "support/in_child.h"
#include "support/sandbox_probes.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

ChildResult shell(const std::string& script, ChildLimits limits = {}) {
    return runChild({"/bin/sh", "-c", script}, limits);
}

fs::path freshFolder(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / ("voxlab_child_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

bool processGone(pid_t pid) {
    // Gone, or a zombie waiting for init to reap it: either way it runs no more.
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    if (!stat) return true;
    std::string line;
    std::getline(stat, line);
    const std::size_t close = line.rfind(')');
    return close != std::string::npos && line.size() > close + 2 && line[close + 2] == 'Z';
}

TEST(ChildProcess, ExitStatusAndOutput) {
    const ChildResult r = shell("echo out; echo err >&2; exit 3");
    EXPECT_EQ(r.exitCode, 3);
    EXPECT_FALSE(r.succeeded());
    EXPECT_NE(r.output.find("out"), std::string::npos);
    EXPECT_NE(r.output.find("err"), std::string::npos);
    EXPECT_EQ(r.describe(60), "exit status 3");
    EXPECT_TRUE(shell("true").succeeded());
}

TEST(ChildProcess, TimeoutKillsTheWholeProcessGroup) {
    ChildLimits limits;
    limits.seconds = 0.5;
    const auto start = std::chrono::steady_clock::now();
    // The shell starts a grandchild and prints its pid; both must die.
    const ChildResult r = shell("sleep 30 & echo $!; wait", limits);
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_TRUE(r.timedOut);
    EXPECT_LT(took, 3.0) << "the limit was 0.5 s";
    EXPECT_EQ(r.describe(0.5), "timed out after 0.5 s");
    const pid_t grandchild = pid_t(std::stol(r.output));
    bool gone = false;
    for (int i = 0; i < 50 && !gone; ++i) {
        gone = processGone(grandchild);
        if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    EXPECT_TRUE(gone) << "the grandchild " << grandchild << " outlived the timeout";
}

TEST(ChildProcess, CrashIsReportedBySignal) {
    const ChildResult r = shell("kill -SEGV $$");
    EXPECT_EQ(r.signal, SIGSEGV);
    EXPECT_FALSE(r.timedOut);
    EXPECT_EQ(r.describe(60), "crashed (Segmentation fault)");
}

TEST(ChildProcess, MemoryCapStopsARunawayAllocation) {
    if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "needs /usr/bin/python3";
#if defined(__SANITIZE_ADDRESS__) || defined(VOXLAB_SANITIZED)
    GTEST_SKIP() << "a sanitizer build sets no address-space cap (its children reserve terabytes)";
#endif
    ChildLimits limits;
    limits.memoryBytes = std::size_t(512) << 20;
    // 2 GiB cannot fit under a 512 MiB address-space cap.
    const ChildResult capped = runChild({"/usr/bin/python3", "-c", "x = bytearray(2 << 30); print('allocated')"},
                                        limits);
    EXPECT_FALSE(capped.succeeded());
    EXPECT_EQ(capped.output.find("allocated"), std::string::npos);
    EXPECT_NE(capped.output.find("MemoryError"), std::string::npos) << capped.output;
    // Without the cap the same program would be limited only by the machine;
    // a small allocation under the cap works.
    const ChildResult small = runChild({"/usr/bin/python3", "-c", "x = bytearray(16 << 20); print('allocated')"},
                                       limits);
    EXPECT_TRUE(small.succeeded()) << small.output;
}

TEST(ChildProcess, WritesAreConfinedToTheWritableFolders) {
    if (!sandboxAvailable()) GTEST_SKIP() << "this kernel has no Landlock";
    const fs::path inside = freshFolder("inside"), outside = freshFolder("outside");
    ChildLimits limits;
    limits.writable = {inside.string()};
    const ChildResult r = shell("echo a > '" + (inside / "ok.txt").string() + "'; echo b > '" +
                                    (outside / "escaped.txt").string() + "'; rm -f '" +
                                    (outside / "keep.txt").string() + "'; echo c > /dev/null",
                                limits);
    EXPECT_TRUE(r.sandboxed);
    EXPECT_TRUE(fs::exists(inside / "ok.txt"));
    EXPECT_FALSE(fs::exists(outside / "escaped.txt")) << r.output;
    // The same script without confinement writes both (the test can fail).
    std::ofstream(outside / "keep.txt") << "x";
    const ChildResult free = shell("echo b > '" + (outside / "escaped.txt").string() + "'");
    EXPECT_FALSE(free.sandboxed);
    EXPECT_TRUE(fs::exists(outside / "escaped.txt"));
    fs::remove_all(inside);
    fs::remove_all(outside);
}

TEST(ChildProcess, EnvironmentAndWorkingDirectory) {
    const fs::path dir = freshFolder("cwd");
    ChildLimits limits;
    limits.workingDir = dir.string();
    limits.environment = {{"VOXLAB_CHILD_TEST", "seven"}};
    const ChildResult r = shell("pwd; echo $VOXLAB_CHILD_TEST", limits);
    EXPECT_NE(r.output.find(dir.filename().string()), std::string::npos);
    EXPECT_NE(r.output.find("seven"), std::string::npos);
    fs::remove_all(dir);
}

TEST(ChildProcess, AMissingProgramIsAnExitStatus) {
    const ChildResult r = runChild({"/nonexistent/voxlab"}, {});
    EXPECT_EQ(r.exitCode, 127);
    EXPECT_NE(r.output.find("cannot execute"), std::string::npos);
    EXPECT_THROW(runChild({}, {}), Error);
}


// --- Isolation (ChildLimits::isolate): what a hostile submission tries. ---

// An isolated child that may run the system's commands (the grader's
// children may not: they are given their programs one by one).
ChildLimits isolated(double seconds = 10) {
    ChildLimits limits;
    limits.isolate = true;
    limits.seconds = seconds;
    limits.readable = {"/usr/bin", "/bin"};
    return limits;
}

bool hasLayer(const ChildResult& r, const std::string& layer) {
    return std::find(r.sandbox.begin(), r.sandbox.end(), layer) != r.sandbox.end();
}

TEST(ChildIsolation, DetachedDescendantsDieWithTheChild) {
    const std::string token = "voxlab_detached_" + std::to_string(getpid());
    // setsid leaves the process group, so killing the group alone misses it.
    // (Loops of short sleeps, so that each long-lived process names the token.)
    const std::string loop = "setsid sh -c 'while :; do sleep 0.2; done' " + token + " & ";
    const std::string script = loop + loop + "sleep 0.3; echo started";
    const ChildResult free = shell(script);  // without isolation they outlive it (the test can fail)
    EXPECT_EQ(processesWith(token), 2) << free.output;
    std::system(("pkill -f " + token).c_str());
    const ChildResult r = shell(script, isolated());
    EXPECT_TRUE(r.succeeded()) << r.output;
    // Either layer ends them: the PID namespace, or killing the pids cgroup.
    if (!hasLayer(r, "pid, network and ipc namespaces") && !hasLayer(r, "pids cgroup"))
        GTEST_SKIP() << "neither namespaces nor a pids cgroup here";
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    EXPECT_EQ(processesWith(token), 0);
    // Also when the time limit ends it.
    const ChildResult t = shell(script + "; sleep 300", isolated(1.0));
    EXPECT_TRUE(t.timedOut);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    EXPECT_EQ(processesWith(token), 0);
}

TEST(ChildIsolation, CannotSignalTheParent) {
    // If the sandbox failed, this test process would die (and the test fail).
    const std::vector<std::string> layers = sandboxLayers();
    const bool namespaces = std::count(layers.begin(), layers.end(), "pid, network and ipc namespaces") > 0;
    if (!namespaces && !std::count(layers.begin(), layers.end(), "landlock signal scope"))
        GTEST_SKIP() << "neither a PID namespace nor Landlock's signal scope here";
    ChildLimits limits = isolated();
    limits.environment["VOXLAB_PARENT"] = std::to_string(getpid());
    const ChildResult r = shell("kill -9 $VOXLAB_PARENT; echo \"kill: $?\"; kill -9 $PPID; echo \"ppid $PPID\"",
                                limits);
    EXPECT_NE(r.output.find("kill: 1"), std::string::npos) << r.output;
    if (namespaces) EXPECT_NE(r.output.find("ppid 0"), std::string::npos) << r.output;  // no parent inside it
}

TEST(ChildIsolation, HasNoNetwork) {
    LoopbackServer server;
    ASSERT_TRUE(server.bound());
    const std::string script = "echo payload > /dev/tcp/127.0.0.1/" + std::to_string(server.port()) + " && echo sent";
    const ChildResult free = runChild({"/bin/bash", "-c", script}, {});
    EXPECT_TRUE(server.received(300)) << free.output;  // the channel works without isolation
    const ChildResult r = runChild({"/bin/bash", "-c", script}, isolated());
    EXPECT_FALSE(server.received(300)) << r.output;
    EXPECT_EQ(r.output.find("sent"), std::string::npos) << r.output;
}

TEST(ChildIsolation, ReadsOnlyWhatItIsGiven) {
    if (!sandboxAvailable()) GTEST_SKIP() << "this kernel has no Landlock";
    const fs::path open = freshFolder("readable"), secret = freshFolder("secret");
    std::ofstream(open / "a.txt") << "visible";
    std::ofstream(secret / "b.txt") << "hidden";
    ChildLimits limits = isolated();
    limits.readable.push_back(open.string());
    const std::string script = "cat " + (open / "a.txt").string() + " " + (secret / "b.txt").string() +
                               "; ls " + secret.string() + "; echo x > " + (open / "c.txt").string();
    const ChildResult r = shell(script, limits);
    EXPECT_TRUE(hasLayer(r, "landlock reads"));
    EXPECT_NE(r.output.find("visible"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("hidden"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("cannot open directory"), std::string::npos) << r.output;  // nor list it
    EXPECT_FALSE(fs::exists(open / "c.txt"));  // readable is not writable
    EXPECT_NE(shell(script).output.find("hidden"), std::string::npos);  // the test can fail
    fs::remove_all(open);
    fs::remove_all(secret);
}

TEST(ChildIsolation, ProcessCountIsLimited) {
    ChildLimits limits = isolated(20);
    limits.maxProcesses = 16;
    // 60 sleepers at once; the shell (dash: echo is built in) counts those
    // it could start, and stops at the first fork that fails.
    const ChildResult r = shell("i=0; while [ $i -lt 60 ]; do sleep 30 & i=$((i+1)); echo started $i; done", limits);
    int up = 0;
    for (std::size_t at = r.output.find("started "); at != std::string::npos; at = r.output.find("started ", at + 1))
        up = std::max(up, std::atoi(r.output.c_str() + at + 8));
    EXPECT_TRUE(hasLayer(r, "pids cgroup") || hasLayer(r, "process limit (RLIMIT_NPROC)")) << r.output;
    EXPECT_LT(up, 16) << r.output;
    EXPECT_GT(up, 0) << r.output;
}

TEST(ChildIsolation, ResultsChannelIsFileDescriptorThree) {
    ChildLimits limits = isolated();
    limits.resultsBytes = 8;
    const ChildResult r = shell("printf 'one two three' >&3; echo done", limits);
    EXPECT_EQ(r.results, "one two ");
    EXPECT_TRUE(r.resultsTruncated);
    EXPECT_NE(r.output.find("done"), std::string::npos);
    EXPECT_EQ(shell("printf x >&3 || echo no-fd-3").output.find("no-fd-3") != std::string::npos, true);
}

// --- Default deny (issue 32): each attack a stage could mount, run by
// tests/support/sandbox_attack.cpp inside the sandbox, and where it is
// harmless also outside it, so that each test can fail. ---

std::string attack(const std::vector<std::string>& args, ChildLimits limits = isolated()) {
    std::vector<std::string> argv = {VOXLAB_SANDBOX_ATTACK};
    argv.insert(argv.end(), args.begin(), args.end());
    limits.readable.push_back(VOXLAB_SANDBOX_ATTACK);
    return runChild(argv, limits).output;
}

bool root() { return geteuid() == 0; }

TEST(ChildSandbox, HoldsNoCapabilityEvenAsRoot) {
    const ChildResult r = runChild({VOXLAB_SANDBOX_ATTACK, "capabilities"}, isolated());
    EXPECT_NE(r.output.find("capabilities: denied"), std::string::npos) << r.output;
    EXPECT_TRUE(hasLayer(r, "no capabilities")) << r.output;
    if (root()) EXPECT_NE(attack({"capabilities"}, {}).find("capabilities: allowed"), std::string::npos);
}

TEST(ChildSandbox, SystemCallsOffTheListFailWithEperm) {
    char hostBefore[256] = {}, hostAfter[256] = {};
    gethostname(hostBefore, sizeof hostBefore);
    for (const char* a : {"keyring", "hostname", "nice", "fifo", "inet", "mount", "unshare", "clone-newuser", "bpf",
                          "perf", "io_uring", "userfaultfd", "ptrace"})
        EXPECT_NE(attack({a}).find(std::string(a) + ": denied (EPERM)"), std::string::npos) << attack({a});
    gethostname(hostAfter, sizeof hostAfter);
    EXPECT_STREQ(hostBefore, hostAfter);
    // No key was left in this user's keyring (KEYCTL_SEARCH: ENOKEY).
    EXPECT_EQ(syscall(SYS_keyctl, 10, -4, "user", "voxlab-hostile-key", 0), -1);
    EXPECT_EQ(errno, ENOKEY);
    EXPECT_NE(attack({"inet"}, {}).find("inet: allowed"), std::string::npos);  // the probe can tell
    EXPECT_NE(attack({"io_uring"}, {}).find("io_uring: allowed"), std::string::npos);
}

TEST(ChildSandbox, OnlyHarmlessDevices) {
    for (const char* a : {"blockdev", "kmsg"}) {
        const std::string out = attack({a});
        EXPECT_NE(out.find(std::string(a) + ": denied"), std::string::npos) << out;
        EXPECT_EQ(out.find("opened"), std::string::npos) << out;
    }
    if (root()) {  // root outside the sandbox opens them (opened and closed, nothing read or written)
        EXPECT_NE(attack({"kmsg"}, {}).find("kmsg: allowed"), std::string::npos);
        const std::string block = attack({"blockdev"}, {});
        if (block.find("denied (ENOENT)") == std::string::npos) EXPECT_NE(block.find("allowed"), std::string::npos);
    }
}

TEST(ChildSandbox, NoUnixSocketOfTheMachine) {
    const fs::path dir = freshFolder("agent");
    const std::string path = (dir / "agent.sock").string();
    const int server = socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
    ASSERT_EQ(bind(server, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    listen(server, 4);
    ChildLimits limits = isolated();
    limits.readable.push_back(dir.string());  // even where the socket's folder is readable
    EXPECT_NE(attack({"unix", path}, limits).find("unix: denied (EPERM)"), std::string::npos);
    pollfd p = {server, POLLIN, 0};
    EXPECT_EQ(poll(&p, 1, 200), 0) << "a connection arrived";
    EXPECT_NE(attack({"unix", path}, {}).find("unix: allowed"), std::string::npos);  // the probe can tell
    close(server);
    fs::remove_all(dir);
}

TEST(ChildSandbox, TheEnvironmentIsAnAllowList) {
    setenv("GRADER_API_TOKEN", "voxlab-secret-token", 1);
    setenv("SSH_AUTH_SOCK", "/tmp/agent.sock", 1);
    setenv("GALLIUM_DRIVER", "llvmpipe", 1);
    ChildLimits limits = isolated();
    limits.environment["VOXLAB_GIVEN"] = "yes";
    EXPECT_NE(attack({"env", "GRADER_API_TOKEN"}, limits).find("=unset"), std::string::npos);
    EXPECT_NE(attack({"env", "SSH_AUTH_SOCK"}, limits).find("=unset"), std::string::npos);
    EXPECT_NE(attack({"env", "GALLIUM_DRIVER"}, limits).find("=llvmpipe"), std::string::npos);  // the GL's settings cross
    EXPECT_NE(attack({"env", "VOXLAB_GIVEN"}, limits).find("=yes"), std::string::npos);
    EXPECT_NE(attack({"env", "PATH"}, limits).find("=/usr/local/bin:/usr/bin:/bin"), std::string::npos);
    EXPECT_NE(attack({"env", "GRADER_API_TOKEN"}, {}).find("=voxlab-secret-token"), std::string::npos);
    unsetenv("GRADER_API_TOKEN");
    unsetenv("SSH_AUTH_SOCK");
    unsetenv("GALLIUM_DRIVER");
}

TEST(ChildSandbox, OneMemoryCapForEverythingItStarts) {
    ChildLimits limits = isolated(30);
    limits.memoryBytes = std::size_t(512) << 20;
    const ChildResult memfd = runChild({VOXLAB_SANDBOX_ATTACK, "memfd", "2048"}, limits);
    if (!hasLayer(memfd, "memory cgroup")) GTEST_SKIP() << "no memory cgroup here: " << memfd.output;
    // A memfd's pages are no process's address space; the cgroup counts them.
    EXPECT_EQ(memfd.output.find("held 2048 MiB"), std::string::npos) << memfd.output;
    EXPECT_TRUE(memfd.outOfMemory) << memfd.output;
    EXPECT_NE(memfd.describe(30).find("ran out of memory"), std::string::npos);
    // Six children of 200 MiB each stay under a per-process cap of 512 MiB,
    // not under one cap of 512 MiB for all of them.
    const ChildResult kids = runChild({VOXLAB_SANDBOX_ATTACK, "children", "6", "200"}, limits);
    EXPECT_EQ(kids.output.find("6 of 6"), std::string::npos) << kids.output;
    EXPECT_TRUE(kids.outOfMemory) << kids.output;
    limits.memoryBytes = std::size_t(2048) << 20;  // with room, they all run (the test can fail)
    EXPECT_NE(runChild({VOXLAB_SANDBOX_ATTACK, "children", "6", "200"}, limits).output.find("6 of 6"),
              std::string::npos);
}

TEST(ChildSandbox, WritesAreCappedInSizeAndTheScratchVanishes) {
    const fs::path dir = freshFolder("scratch"), scratch = dir / "tmp";
    fs::create_directories(scratch);
    ChildLimits limits = isolated(30);
    limits.writable = {dir.string()};
    limits.scratch = scratch.string();
    limits.scratchBytes = std::size_t(32) << 20;
    const ChildResult inScratch = runChild({VOXLAB_SANDBOX_ATTACK, "write", (scratch / "big").string(), "100"}, limits);
    if (!hasLayer(inScratch, "size-capped scratch (tmpfs)")) GTEST_SKIP() << "no mount namespace here";
    EXPECT_NE(inScratch.output.find("wrote 3"), std::string::npos) << inScratch.output;  // 30-32 of 100 MiB
    EXPECT_TRUE(fs::is_empty(scratch)) << "the scratch's files outlived the child";
    limits.fileBytes = std::size_t(16) << 20;
    const ChildResult outside = runChild({VOXLAB_SANDBOX_ATTACK, "write", (dir / "big").string(), "100"}, limits);
    EXPECT_NE(outside.output.find("wrote 16 MiB"), std::string::npos) << outside.output;
    EXPECT_EQ(fs::file_size(dir / "big"), std::uintmax_t(16) << 20);
    fs::remove_all(dir);
}

// The same attacks by a grader that runs as a plain user: everything but
// the cgroups (which need root or delegation) holds, and the report says
// which layers are missing.
TEST(ChildSandbox, AsAPlainUserToo) {
    if (!root()) GTEST_SKIP() << "needs root to drop to a plain user";
    const std::string got = messageInChild(
        // (A process that changed its ids is not dumpable, and so may not
        // write its own /proc/self/uid_map: a user's own process is.)
        [] { return setgid(65534) == 0 && setuid(65534) == 0 && prctl(PR_SET_DUMPABLE, 1) == 0; },
        [] {
            const ChildResult r = runChild({VOXLAB_SANDBOX_ATTACK, "capabilities"}, isolated());
            std::string out = r.output;
            for (const char* a : {"keyring", "hostname", "inet", "mount", "unshare"}) out += attack({a});
            out += "layers:";
            for (const std::string& l : r.sandbox) out += " [" + l + "]";
            out += "\nmissing:";
            for (const std::string& l : r.sandboxMissing) out += " [" + l + "]";
            return out;
        });
    std::cout << got << "\n";
    EXPECT_NE(got.find("capabilities: denied"), std::string::npos) << got;
    for (const char* a : {"keyring", "hostname", "inet", "mount", "unshare"})
        EXPECT_NE(got.find(std::string(a) + ": denied (EPERM)"), std::string::npos) << got;
    EXPECT_NE(got.find("[system-call allow-list (seccomp)]"), std::string::npos) << got;
    EXPECT_NE(got.find("[memory cgroup]", got.find("missing:")), std::string::npos) << got;
}

}  // namespace
}  // namespace voxlab::testing
