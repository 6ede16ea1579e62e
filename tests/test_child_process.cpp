// Child processes with limits (voxlab/child_process.h): what the grader
// relies on to survive a submission that hangs, crashes, eats memory or
// writes where it should not.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "voxlab/child_process.h"
#include "voxlab/error.h"

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

}  // namespace
}  // namespace voxlab::testing
