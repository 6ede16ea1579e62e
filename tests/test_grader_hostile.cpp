// Hostile submissions against the grader (issue: "the grader cannot be
// cheated or harmed by a submission"). Each test is an attack a student can
// actually mount, graded for real through gradeSubmissions(), and asserts:
//   - no unearned points: the score is what the honest part of the
//     submission earns (0 for a stub);
//   - nothing outside the report folder changed (fingerprints of reference/,
//     the submission and a canary folder beside the report);
//   - no process it started is left running (each names a unique token);
//   - the grader finished and wrote its report.
// Where an attack's code runs, it also prints a marker, so the test shows
// that the attack really ran and the defence, not an accident, stopped it.
#include <gtest/gtest.h>

#include <poll.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "voxlab/child_process.h"
#include "voxlab/expected_cache.h"
#include "voxlab/grader.h"
#include "voxlab/image.h"
#include "voxlab/stage_library.h"
#include "support/expected_outputs.h"
#include "support/run_command.h"
#include "support/sandbox_probes.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSource = VOXLAB_SOURCE_DIR;

fs::path scratchRoot() { return fs::path(::testing::TempDir()) / ("voxlab_hostile_" + std::to_string(getpid())); }

fs::path scratch(const std::string& name) {
    const fs::path dir = scratchRoot() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string fingerprint(const fs::path& root) {
    std::vector<std::string> entries;
    for (const auto& e : fs::recursive_directory_iterator(root))
        entries.push_back(fs::relative(e.path(), root).string() + "|" +
                          (e.is_symlink() ? "link" : e.is_regular_file() ? readFile(e.path()) : "dir"));
    std::sort(entries.begin(), entries.end());
    std::string all;
    for (const std::string& s : entries) all += s + "\n";
    return std::to_string(all.size()) + ":" + std::to_string(std::hash<std::string>{}(all));
}

// A C++ stage (texslice3d) whose file is the starter stub plus `attack`, a
// function body run when the stage library is loaded.
std::string hostileCpp(const std::string& attack, const std::string& includes = "") {
    std::string stub = readFile((kSource / "assignments/texslice3d/proxy_geometry.cpp").string());
    return "#include <cstdio>\n#include <cstdlib>\n#include <cstring>\n#include <fcntl.h>\n#include <signal.h>\n"
           "#include <unistd.h>\n#include <fstream>\n#include <sstream>\n#include <string>\n" +
           includes + stub + "\nnamespace {\nint hostile() {\n" + attack +
           "\n    return 0;\n}\nconst int hostileRan = hostile();\n}  // namespace\n";
}

class HostileSubmissions : public ExpectedOutputsSuite<HostileSubmissions> {
public:
    static fs::path expectedFolder() { return scratch("expected"); }
    static void TearDownTestSuite() { if (!std::getenv("VOXLAB_KEEP")) fs::remove_all(scratchRoot()); }
    static GraderOptions options() {
        GraderOptions o = referenceOptions();
        o.stages = {"mip", "composite", "texslice3d", "attenuated_mip"};
        o.jobs = 1;
        o.timeLimit = 20;
        return o;
    }

    // Grades `submission`'s `stage` and checks the invariants above; returns
    // the stage's entry of the report.
    // With `renderExpected`, the run renders (or copies from the cache) the
    // expected outputs itself, as `voxlab grade` does, instead of using the
    // suite's.
    json gradeAndCheck(const fs::path& submission, const std::string& stage, const std::string& token = "",
                       bool renderExpected = false, std::size_t memoryLimit = 0) {
        const fs::path report = scratch("report_" + stage) / "report";
        const fs::path canary = report.parent_path() / "canary";
        fs::create_directories(canary);
        std::ofstream(canary / "keep.txt") << "canary";
        const std::string before = fingerprint(kSource / "reference") + fingerprint(submission) + fingerprint(canary);
        GraderOptions o = options();
        o.stages = {stage};
        if (memoryLimit > 0) o.memoryLimit = memoryLimit;
        if (renderExpected) {
            o.shipped = false;
            o.expectedDir = (report.parent_path() / "expected").string();
        }
        const json result = gradeSubmissions({{"hostile", submission.string(), report.string()}}, o).at(0);
        EXPECT_EQ(before, fingerprint(kSource / "reference") + fingerprint(submission) + fingerprint(canary))
            << "something outside the report folder changed";
        EXPECT_TRUE(fs::exists(report / "report.json"));
        EXPECT_TRUE(fs::exists(report / "index.html"));
        if (!token.empty()) EXPECT_EQ(processesWith(token), 0) << "a process of the submission outlived grading";
        report_ = readFile((report / "report.json").string()) + readFile((report / "index.html").string());
        return result.at("stages").at(0);
    }

    // A submission folder holding one stage, a copy of the reference's or
    // of the starter code's.
    static fs::path submissionWith(const std::string& name, const std::string& stage, const std::string& from) {
        const fs::path sub = scratch("sub_" + name);
        fs::copy(kSource / from / stage, sub / stage, fs::copy_options::recursive);
        return sub;
    }

    std::string report_;  // report.json and index.html of the last grading
};

// --- The graded stage comes only from the submission. ---

TEST_F(HostileSubmissions, AnEmptyStageFolderScoresNothing) {
    const fs::path sub = scratch("empty");
    fs::create_directories(sub / "mip");
    const json s = gradeAndCheck(sub, "mip");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_EQ(s["status"], "not_implemented") << s["message"];
    EXPECT_NE(s["message"].get<std::string>().find("mip/mip.glsl is missing"), std::string::npos) << s["message"];
}

TEST_F(HostileSubmissions, ADeletedOrBlankStageFileScoresNothing) {
    fs::path sub = submissionWith("deleted", "mip", "reference");
    fs::remove(sub / "mip/mip.glsl");
    EXPECT_EQ(gradeAndCheck(sub, "mip")["score"].get<double>(), 0.0);
    std::ofstream(sub / "mip/mip.glsl") << "  \n\t\n";
    const json s = gradeAndCheck(sub, "mip");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(s["message"].get<std::string>().find("is empty"), std::string::npos) << s["message"];
}

TEST_F(HostileSubmissions, IncludesThatLeaveTheSubmissionAreCompileErrors) {
    const std::string absolute = (kSource / "reference/mip/mip.glsl").string();
    for (const std::string& include : {std::string("../reference/mip/mip.glsl"), std::string("../../mip/mip.glsl"),
                                       absolute, std::string("mip/../mip/mip.glsl")}) {
        fs::path sub = submissionWith("include", "mip", "assignments");
        std::ofstream(sub / "mip/mip.glsl") << "#include \"" << include << "\"\n";
        const json s = gradeAndCheck(sub, "mip");
        EXPECT_EQ(s["score"].get<double>(), 0.0) << include;
        EXPECT_EQ(s["status"], "compile_error") << include << ": " << s["message"];
    }
}

TEST_F(HostileSubmissions, ALinkToTheReferenceScoresNothing) {
    fs::path sub = submissionWith("link", "mip", "assignments");
    fs::remove(sub / "mip/mip.glsl");
    fs::create_symlink(kSource / "reference/mip/mip.glsl", sub / "mip/mip.glsl");
    json s = gradeAndCheck(sub, "mip");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(s["message"].get<std::string>().find("is a link"), std::string::npos) << s["message"];
    // A helper linked in and included: the link is not copied, the include fails.
    fs::remove(sub / "mip/mip.glsl");
    std::ofstream(sub / "mip/mip.glsl") << "#include \"mip/solution.glsl\"\n";
    fs::create_symlink(kSource / "reference/mip/mip.glsl", sub / "mip/solution.glsl");
    s = gradeAndCheck(sub, "mip");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_EQ(s["status"], "compile_error") << s["message"];
    // The whole stage folder a link to the reference's.
    const fs::path linked = scratch("linked_folder");
    fs::create_directory_symlink(kSource / "reference/mip", linked / "mip");
    s = gradeAndCheck(linked, "mip");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(s["message"].get<std::string>().find("not a folder"), std::string::npos) << s["message"];
    // A FIFO where the file should be: refused at once, not waited on.
    fs::remove(sub / "mip/mip.glsl");
    ASSERT_EQ(mkfifo((sub / "mip/mip.glsl").c_str(), 0600), 0);
    s = gradeAndCheck(sub, "mip");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(s["message"].get<std::string>().find("not a regular file"), std::string::npos) << s["message"];
}

TEST_F(HostileSubmissions, AnOversizedStageFileIsAnError) {
    fs::path sub = submissionWith("padded", "mip", "assignments");
    std::ofstream(sub / "mip/mip.glsl", std::ios::app) << std::string(5 << 20, ' ') << "\n";
    const json s = gradeAndCheck(sub, "mip");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_EQ(s["status"], "error");
    EXPECT_NE(s["message"].get<std::string>().find("over the limit"), std::string::npos) << s["message"];
}

TEST_F(HostileSubmissions, ACppFileBesideAGlslStageIsNotCompiled) {
    // A stub composite.glsl and a helper.cpp that would print a marker (and,
    // in the attack that was found, copy the expected images) when loaded.
    fs::path sub = submissionWith("helper", "composite", "assignments");
    std::ofstream(sub / "composite/helper.cpp")
        << "#include <cstdio>\nstatic int ran = [] { std::puts(\"HOSTILE-HELPER-RAN\"); return 1; }();\n";
    const json s = gradeAndCheck(sub, "composite");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_EQ(report_.find("HOSTILE-HELPER-RAN"), std::string::npos);
}

// --- A C++ stage's code runs boxed in. ---

// The stage folders hold the stages' oracle tests and check code beside
// their shaders: neither may reach a graded stage (the grading worker reads
// the folders' shader files only; the stage host, where C++ runs, none).
TEST_F(HostileSubmissions, CppCannotReadTheReferenceOrTheExpectedOutputs) {
    const std::string reference = (kSource / "reference/mip/mip.glsl").string();
    const std::string expected = (fs::path(options().expectedDir) / "texslice3d/bucky_oblique.png").string();
    const std::string oracle = (kSource / "framework/stages/marching_cubes/test_marching_cubes.cpp").string();
    const std::string check = (kSource / "framework/stages/texslice3d/check.cpp").string();
    const std::string attack =
        "    std::puts(\"HOSTILE-RAN\");\n"
        "    for (const char* path : {\"" + reference + "\", \"" + expected + "\", \"" + oracle + "\", \"" + check +
        "\", \"/etc/shadow\"}) {\n"
        "        std::ifstream in(path);\n"
        "        std::stringstream s; s << in.rdbuf();\n"
        "        if (in && s.str().size() > 0) std::printf(\"LEAKED %s\\n\", path);\n"
        "    }\n"
        "    std::fflush(stdout);\n"
        "    std::abort();  // so that the report shows the log\n";
    fs::path sub = submissionWith("reader", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp") << hostileCpp(attack);
    const json s = gradeAndCheck(sub, "texslice3d");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(report_.find("HOSTILE-RAN"), std::string::npos) << "the attack did not run: " << s["message"];
    EXPECT_EQ(report_.find("LEAKED"), std::string::npos);
}

TEST_F(HostileSubmissions, CppCannotIncludeTheReferenceAtCompileTime) {
    // The compiler's error log would show the included file's lines.
    fs::path sub = submissionWith("compile_reader", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp")
        << "#include \"" << (kSource / "reference/texslice3d/proxy_geometry.cpp").string() << "\"\n";
    const json s = gradeAndCheck(sub, "texslice3d");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_EQ(s["status"], "compile_error") << s["message"];
    EXPECT_EQ(report_.find("dot(n, a + t (b - a))"), std::string::npos) << "the reference's text reached the report";
}

TEST_F(HostileSubmissions, CppCannotWriteOutsideOrPlantLinks) {
    const fs::path report = scratchRoot() / "report_texslice3d" / "report";
    const std::string targets[] = {(kSource / "reference/texslice2d/README.md").string(),
                                   (report.parent_path() / "canary/keep.txt").string(),
                                   (report / "index.html").string(), "/tmp/voxlab_hostile_was_here"};
    std::string attack = "    std::puts(\"HOSTILE-RAN\");\n";
    for (const std::string& t : targets)
        attack += "    if (std::FILE* f = std::fopen(\"" + t + "\", \"a\")) { std::fputs(\"x\", f); std::fclose(f); "
                  "std::puts(\"WROTE " + t + "\"); }\n";
    attack += "    if (symlink(\"" + targets[0] + "\", \"" + (report / "texslice3d/bucky_oblique.submission.png").string() +
              "\") == 0) std::puts(\"WROTE link\");\n    std::fflush(stdout);\n    std::abort();\n";
    fs::path sub = submissionWith("writer", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp") << hostileCpp(attack);
    const json s = gradeAndCheck(sub, "texslice3d");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(report_.find("HOSTILE-RAN"), std::string::npos) << s["message"];
    EXPECT_EQ(report_.find("WROTE"), std::string::npos);
    EXPECT_FALSE(fs::exists("/tmp/voxlab_hostile_was_here"));
}

// The expected-output cache (voxlab/expected_cache.h) outlives the run: a
// submission that overwrote an expected image there would be graded against
// its own picture next time. The attack rewrites every file of the cache,
// plants one, and reads one; none of it may work, and the reference still
// scores full marks from the cache afterwards.
TEST_F(HostileSubmissions, CppCannotPoisonTheCache) {
    const std::optional<std::string> cache = expected_cache::folder();
    ASSERT_TRUE(cache) << "the cache is off: this test needs VOXLAB_EXPECTED_CACHE (tests/CMakeLists.txt sets it)";
    GraderOptions warm = options();  // the cache holds texslice3d's outputs before the attack
    warm.stages = {"texslice3d"};
    warm.expectedDir = scratch("warm").string();
    renderExpectedOutputs(warm);
    // This reference's entry (other tests may add entries of their own meanwhile).
    const fs::path entry = fs::path(*cache) / expected_cache::key(VOXLAB_BINARY, (kSource / "reference").string());
    auto entryFingerprint = [&] {
        return fingerprint(entry / "texslice3d") + readFile((entry / "reference_stages.so").string());
    };
    const std::string before = entryFingerprint();
    const std::string walk = "    std::error_code ec;\n"
                             "    for (std::filesystem::recursive_directory_iterator it(\"" + *cache + "\", ec), end; !ec && it != end;"
                             " it.increment(ec)) {\n"
                             "        if (!it->is_regular_file(ec)) continue;\n"
                             "        if (std::ifstream in{it->path()}; in.get() != EOF) std::puts(\"READ cache\");\n"
                             "        if (std::FILE* f = std::fopen(it->path().c_str(), \"r+\")) { std::fputs(\"x\", f); std::fclose(f);"
                             " std::puts(\"WROTE cache\"); }\n    }\n";
    const std::string attack = "    std::puts(\"HOSTILE-RAN\");\n" + walk + "    if (std::FILE* f = std::fopen(\"" + *cache +
                               "/planted\", \"w\")) { std::fclose(f); std::puts(\"WROTE planted\"); }\n    std::fflush(stdout);\n";
    fs::path sub = submissionWith("poisoner", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp") << hostileCpp(attack, "#include <filesystem>\n");
    const json s = gradeAndCheck(sub, "texslice3d", "", true);
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(report_.find("HOSTILE-RAN"), std::string::npos) << s["message"];
    EXPECT_EQ(report_.find("WROTE"), std::string::npos);
    EXPECT_EQ(report_.find("READ"), std::string::npos);
    EXPECT_EQ(before, entryFingerprint()) << "the cache changed";
    EXPECT_FALSE(fs::exists(fs::path(*cache) / "planted"));
    const json honest = gradeAndCheck(submissionWith("honest", "texslice3d", "reference"), "texslice3d", "", true);
    EXPECT_EQ(honest["status"], "passed") << honest["message"];
}

TEST_F(HostileSubmissions, CppCannotKillTheGraderOrLeaveProcesses) {
    const std::string token = "voxlab_hostile_" + std::to_string(getpid());
    setenv("VOXLAB_HOSTILE_TARGET", std::to_string(getpid()).c_str(), 1);
    const std::string attack =
        "    for (int i = 0; i < 3; ++i) if (fork() == 0) { setsid(); execl(\"/bin/sh\", \"sh\", \"-c\", "
        "\"while :; do sleep 0.2; done\", \"" + token + "\", (char*)nullptr); _exit(0); }\n"
        "    for (int i = 0; i < 500; ++i) if (fork() == 0) { pause(); _exit(0); }  // a fork bomb, bounded\n"
        "    kill(std::atoi(std::getenv(\"VOXLAB_HOSTILE_TARGET\")), SIGKILL);  // the grader (this test)\n"
        "    kill(getppid(), SIGKILL);\n";
    fs::path sub = submissionWith("killer", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp") << hostileCpp(attack);
    const json s = gradeAndCheck(sub, "texslice3d", token);
    EXPECT_EQ(s["score"].get<double>(), 0.0);  // and this process is still alive to say so
}

TEST_F(HostileSubmissions, CppHasNoNetwork) {
    LoopbackServer server;
    ASSERT_TRUE(server.bound());
    const std::string attack =
        "    int s = socket(AF_INET, SOCK_STREAM, 0);\n    sockaddr_in a{};\n    a.sin_family = AF_INET;\n"
        "    a.sin_port = htons(" + std::to_string(server.port()) + ");\n"
        "    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);\n"
        "    if (connect(s, (sockaddr*)&a, sizeof a) == 0) { (void)!write(s, \"stolen\", 6); std::puts(\"SENT\"); }\n";
    fs::path sub = submissionWith("network", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp")
        << hostileCpp(attack, "#include <arpa/inet.h>\n#include <netinet/in.h>\n#include <sys/socket.h>\n");
    const json s = gradeAndCheck(sub, "texslice3d");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_FALSE(server.received(200)) << "a connection from the submission arrived";
}

TEST_F(HostileSubmissions, CppCannotForgeResultsEvenWithTheGoldenImages) {
    // Students have the expected images (a release ships them for `voxlab
    // check`). A stub stage that embeds them and writes them to the results
    // channel before the framework renders must not earn the points.
    std::string attack;
    for (const std::string scene : {"bonsai_perspective", "tooth_oblique", "bucky_oblique"}) {
        const Image img = loadPng((fs::path(options().expectedDir) / "texslice3d" / (scene + ".png")).string());
        std::string rgb;
        for (std::size_t i = 0; i < std::size_t(img.width) * img.height; ++i)
            for (int c = 0; c < 3; ++c) rgb += std::to_string(int(toByte(img.rgba[i * 4 + c]))) + ",";
        const std::string header = "{\\\"type\\\":\\\"image\\\",\\\"name\\\":\\\"" + scene + "\\\",\\\"width\\\":" +
                                   std::to_string(img.width) + ",\\\"height\\\":" + std::to_string(img.height) +
                                   ",\\\"bytes\\\":" + std::to_string(rgb.size() ? img.width * img.height * 3 : 0) +
                                   "}\\n";
        attack += "    { static const unsigned char px[] = {" + rgb + "};\n      const char h[] = \"" + header +
                  "\";\n      for (int fd = 3; fd < 64; ++fd) { if (write(fd, h, sizeof h - 1) > 0) "
                  "(void)!write(fd, px, sizeof px); } }\n";
    }
    attack += "    std::puts(\"HOSTILE-RAN\");\n";
    fs::path sub = submissionWith("forger", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp") << hostileCpp(attack);
    const json s = gradeAndCheck(sub, "texslice3d");
    EXPECT_EQ(s["score"].get<double>(), 0.0) << s.dump(1);
}

// --- Default deny: another stage's code, the compiled reference, the
// machine, the grader's environment and resources out of reach. ---

// A stage graded with another stage's reference in the same program could
// call it: attenuated MIP with no attenuation is MIP (found scoring 10/10).
TEST_F(HostileSubmissions, AnotherStagesReferenceCannotStandIn) {
    const std::string head = "#ifndef VOXLAB_STAGE_MIP_GLSL\n#define VOXLAB_STAGE_MIP_GLSL\n#include \"voxlab/ray.glsl\"\n";
    const std::pair<std::string, std::string> attacks[] = {
        {"#include \"attenuated_mip/attenuated_mip.glsl\"\nfloat mip_ray(Ray ray) { return attenuated_mip_ray(ray); }\n",
         "is stage attenuated_mip's file"},
        // A stage the framework itself compiles in (volume.glsl includes cubic).
        {"float mip_ray(Ray ray) { return sample_cubic(ray.origin); }\n", "sample_cubic() belongs to stage cubic"},
        {"#define CALL(a, b) a##b\nfloat mip_ray(Ray ray) { return CALL(sample_, cubic)(ray.origin); }\n",
         "token pasting"}};
    for (const auto& [body, why] : attacks) {
        fs::path sub = submissionWith("other_stage", "mip", "assignments");
        std::ofstream(sub / "mip/mip.glsl") << head << body << "#endif\n";
        const json s = gradeAndCheck(sub, "mip");
        EXPECT_EQ(s["score"].get<double>(), 0.0) << body;
        EXPECT_EQ(s["status"], "compile_error") << s["message"];
        EXPECT_NE(report_.find(why), std::string::npos) << s["message"];
    }
    // A prerequisite is the stage's to use: attenuated MIP calls mip_ray().
    fs::path honest = submissionWith("prerequisite", "attenuated_mip", "reference");
    EXPECT_EQ(gradeAndCheck(honest, "attenuated_mip")["status"], "passed");
}

// The compiled reference: the voxlab binary links the reference's C++
// stages in, and the grader loads them as a library. A build that embeds
// either (.incbin) and calls into it was found scoring 10/10.
TEST_F(HostileSubmissions, TheCompiledReferenceCannotBeEmbedded) {
    const std::string binary = fs::canonical(VOXLAB_BINARY).string();
    const std::string library = (fs::path(options().expectedDir) / "reference_stages.so").string();
    std::ofstream(library) << "a stand-in for the compiled reference";  // wherever the grader keeps it
    for (const std::string& target : {binary, library}) {
        fs::path sub = submissionWith("incbin", "texslice3d", "assignments");
        std::ofstream(sub / "texslice3d/proxy_geometry.cpp", std::ios::app)
            << "asm(\".section .rodata\\n.incbin \\\"" << target << "\\\"\\n.previous\");\n";
        const json s = gradeAndCheck(sub, "texslice3d");
        EXPECT_EQ(s["score"].get<double>(), 0.0) << target;
        EXPECT_EQ(s["status"], "compile_error") << target << ": " << s["message"];
        EXPECT_NE(report_.find("incbin"), std::string::npos) << s["message"];
        // Outside the sandbox the same file builds (the test can fail).
        std::string includes;
        for (const std::string& dir : stageIncludeDirs()) includes += " -I" + dir;
        const CommandResult built = runShell("g++ -std=c++17 -c" + includes + " " +
                                             (sub / "texslice3d/proxy_geometry.cpp").string() + " -o /dev/null");
        EXPECT_EQ(built.exitCode, 0) << built.err;
    }
    fs::remove(library);
}

// The stage host holds no stage code at all, so that a library loaded
// into it cannot find the reference's functions in memory.
TEST_F(HostileSubmissions, TheStageHostHoldsNoStageCode) {
    const fs::path host = fs::path(VOXLAB_BINARY).parent_path() / "voxlab-stage-host";
    ASSERT_TRUE(fs::exists(host));
    const std::string hostSymbols = runShell("nm -C " + host.string()).out;
    const std::string voxlabSymbols = runShell("nm -C " + std::string(VOXLAB_BINARY)).out;
    for (const char* f : {"voxlab::planeBoxPolygon(", "voxlab::chooseSliceAxis(", "voxlab::cubeCase(",
                          "voxlab::edgeCrossing(", "voxlab::splatOrder(", "voxlab::factorShearWarp("}) {
        EXPECT_EQ(hostSymbols.find(f), std::string::npos) << f;
        EXPECT_NE(voxlabSymbols.find(f), std::string::npos) << f;  // where it is (the test can fail)
    }
}

// The host's answers are bounded: a C++ stage returning more values than
// the protocol carries is an error naming the function, not a flood into
// the grader (stage_host_protocol.h's kMaxPoints).
TEST_F(HostileSubmissions, AStagesOversizedResultIsAnErrorNamingIt) {
    fs::path sub = submissionWith("flood", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp")
        << "#include \"voxlab/proxy_geometry.h\"\nnamespace voxlab {\n"
           "std::vector<glm::dvec3> planeBoxPolygon(glm::dvec3, double, glm::dvec3 lo, glm::dvec3) {\n"
           "    return std::vector<glm::dvec3>(100000, lo);\n}\n}  // namespace voxlab\n";
    const json s = gradeAndCheck(sub, "texslice3d");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(report_.find("planeBoxPolygon returned 100000 values (at most 64)"), std::string::npos) << s["message"];
}

// Marching cubes calls its stage in batches (a slab's cubes, then its new
// edges: one round trip each to the stage host). A call that throws in the
// middle of a batch is that batch's answer, named in the report, and the
// calls after it are not made; a case outside 0..255 is refused by name.
TEST_F(HostileSubmissions, AFailingCallInsideABatchIsAnErrorNamingIt) {
    fs::path sub = submissionWith("batch_throw", "marching_cubes", "reference");
    const fs::path file = sub / "marching_cubes/marching_cubes.cpp";
    std::string text = readText(file);
    const std::string signature = "glm::dvec3 edgeCrossing(glm::dvec3 a, glm::dvec3 b, double va, double vb, double isovalue) {";
    ASSERT_NE(text.find(signature), std::string::npos) << "the reference's edgeCrossing changed its signature";
    text.replace(text.find(signature), signature.size(),
                 "glm::dvec3 referenceCrossing(glm::dvec3 a, glm::dvec3 b, double va, double vb, double isovalue) {");
    text += "namespace voxlab {\n"
            "glm::dvec3 edgeCrossing(glm::dvec3 a, glm::dvec3 b, double va, double vb, double isovalue) {\n"
            "    static int calls = 0;\n"
            "    if (++calls == 300) throw std::runtime_error(\"crossing 300 refused\");\n"
            "    return referenceCrossing(a, b, va, vb, isovalue);\n}\n}  // namespace voxlab\n";
    std::ofstream(file) << text;
    const json s = gradeAndCheck(sub, "marching_cubes", "", true);
    EXPECT_LT(s["score"].get<double>(), 10.0);
    EXPECT_NE(report_.find("crossing 300 refused"), std::string::npos) << s["message"];

    sub = submissionWith("batch_case", "marching_cubes", "reference");
    text = readText(sub / "marching_cubes/marching_cubes.cpp");
    const std::string cubeCase = "int cubeCase(const double values[8], double isovalue) {";
    ASSERT_NE(text.find(cubeCase), std::string::npos) << "the reference's cubeCase changed its signature";
    text.replace(text.find(cubeCase), cubeCase.size(), "int referenceCase(const double values[8], double isovalue) {");
    text += "namespace voxlab {\nint cubeCase(const double values[8], double isovalue) {\n"
            "    const int c = referenceCase(values, isovalue);\n    return c == 0 ? c : c + 256;\n}\n}  // namespace voxlab\n";
    std::ofstream(sub / "marching_cubes/marching_cubes.cpp") << text;
    const json t = gradeAndCheck(sub, "marching_cubes", "", true);
    EXPECT_LT(t["score"].get<double>(), 10.0);
    EXPECT_NE(report_.find(", not a case 0..255"), std::string::npos) << t["message"];
}

// A build may not use unbounded memory or disk: an assembler told to
// embed 1.5 GB (the largest system library the compiler may read, over
// and over; a device such as /dev/zero it refuses to embed).
TEST_F(HostileSubmissions, TheBuildIsCappedInMemoryAndDisk) {
    fs::path big;
    for (const auto& e : fs::directory_iterator("/usr/lib/x86_64-linux-gnu"))
        if (e.is_regular_file() && (big.empty() || e.file_size() > fs::file_size(big))) big = e.path();
    ASSERT_FALSE(big.empty());
    const std::size_t copies = std::size_t(1500) / std::max<std::size_t>(1, fs::file_size(big) >> 20) + 1;
    fs::path sub = submissionWith("huge_build", "texslice3d", "assignments");
    std::ofstream out(sub / "texslice3d/proxy_geometry.cpp", std::ios::app);
    for (std::size_t i = 0; i < copies; ++i)
        out << "asm(\".section .rodata\\n.incbin \\\"" << big.string() << "\\\"\\n.previous\");\n";
    out.close();
    const auto start = std::chrono::steady_clock::now();
    const json s = gradeAndCheck(sub, "texslice3d", "", false, std::size_t(1024) << 20);
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_EQ(s["status"], "compile_error") << s["message"];
    EXPECT_EQ(report_.find("unable to include"), std::string::npos) << "the attack did not run: " << s["message"];
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 100.0);
    std::uintmax_t bytes = 0;
    for (const auto& e : fs::recursive_directory_iterator(scratchRoot() / "report_texslice3d"))
        if (e.is_regular_file()) bytes += e.file_size();
    EXPECT_LT(bytes, std::uintmax_t(64) << 20) << "the build wrote into the report folder";
}

// Run as root (as Gradescope's container runs the grader), a stage still
// holds no privilege: the machine is left as it was.
TEST_F(HostileSubmissions, CppAsRootCannotTouchTheMachine) {
    char hostBefore[256] = {}, hostAfter[256] = {};
    gethostname(hostBefore, sizeof hostBefore);
    const std::string attack =
        "    std::puts(\"HOSTILE-RAN\");\n"
        "    if (sethostname(\"owned\", 5) == 0) std::puts(\"ALLOWED hostname\");\n"
        "    if (syscall(SYS_add_key, \"user\", \"voxlab-hostile-key\", \"x\", 1, -4) >= 0) std::puts(\"ALLOWED key\");\n"
        "    if (setpriority(PRIO_PROCESS, 0, -20) == 0) std::puts(\"ALLOWED nice\");\n"
        "    sched_param p{}; p.sched_priority = 1;\n"
        "    if (sched_setscheduler(0, SCHED_FIFO, &p) == 0) std::puts(\"ALLOWED fifo\");\n"
        "    if (open(\"/dev/kmsg\", O_WRONLY) >= 0) std::puts(\"ALLOWED kmsg\");\n"
        "    for (const char* d : {\"/dev/vda\", \"/dev/sda\", \"/dev/nvme0n1\", \"/dev/loop0\", \"/dev/mem\"})\n"
        "        if (open(d, O_RDWR) >= 0) std::printf(\"ALLOWED %s\\n\", d);\n"
        "    if (mount(\"none\", \"/tmp\", \"tmpfs\", 0, nullptr) == 0) std::puts(\"ALLOWED mount\");\n"
        "    std::fflush(stdout);\n    std::abort();\n";
    fs::path sub = submissionWith("root", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp")
        << hostileCpp(attack, "#include <sched.h>\n#include <sys/mount.h>\n#include <sys/resource.h>\n#include <sys/syscall.h>\n");
    const json s = gradeAndCheck(sub, "texslice3d");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(report_.find("HOSTILE-RAN"), std::string::npos) << s["message"];
    EXPECT_EQ(report_.find("ALLOWED"), std::string::npos) << s["message"];
    gethostname(hostAfter, sizeof hostAfter);
    EXPECT_STREQ(hostBefore, hostAfter);
    EXPECT_EQ(syscall(SYS_keyctl, 10, -4, "user", "voxlab-hostile-key", 0), -1);  // KEYCTL_SEARCH: no such key
}

// Nothing of the grader's environment reaches the stage: not a token, not
// the ssh agent's socket.
TEST_F(HostileSubmissions, TheGradersEnvironmentAndSocketsStayOut) {
    const fs::path agent = scratch("agent") / "agent.sock";
    const int server = socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, agent.c_str(), sizeof addr.sun_path - 1);
    ASSERT_EQ(bind(server, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    listen(server, 4);
    setenv("GRADER_API_TOKEN", "voxlab-secret-7c1f", 1);
    setenv("SSH_AUTH_SOCK", agent.c_str(), 1);
    const std::string attack =
        "    std::puts(\"HOSTILE-RAN\");\n"
        "    int s = socket(AF_UNIX, SOCK_STREAM, 0);\n    sockaddr_un a{};\n    a.sun_family = AF_UNIX;\n"
        "    std::strncpy(a.sun_path, \"" + agent.string() + "\", sizeof a.sun_path - 1);\n"
        "    if (connect(s, (sockaddr*)&a, sizeof a) == 0) { (void)!write(s, \"key?\", 4); std::puts(\"CONNECTED\"); }\n"
        "    std::fflush(stdout);\n"
        "    std::string all;\n"
        "    for (char** e = environ; *e; ++e) all += std::string(*e) + \" \";\n"
        "    throw std::runtime_error(\"environment: \" + all);\n";
    fs::path sub = submissionWith("environment", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp")
        << hostileCpp(attack, "#include <stdexcept>\n#include <sys/socket.h>\n#include <sys/un.h>\n");
    const json s = gradeAndCheck(sub, "texslice3d");
    unsetenv("GRADER_API_TOKEN");
    unsetenv("SSH_AUTH_SOCK");
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(report_.find("HOSTILE-RAN"), std::string::npos) << s["message"];
    EXPECT_NE(report_.find("environment: "), std::string::npos) << "the exception did not reach the report";
    EXPECT_EQ(report_.find("voxlab-secret-7c1f"), std::string::npos);
    EXPECT_EQ(report_.find("CONNECTED"), std::string::npos);
    pollfd p = {server, POLLIN, 0};
    EXPECT_EQ(poll(&p, 1, 100), 0) << "the agent's socket was reached";
    close(server);
}

// Memory outside any one process: a memfd, and children each under the
// per-process cap. One cap holds the stage's processes together.
TEST_F(HostileSubmissions, OneMemoryCapHoldsTheWholeStage) {
    if (std::find(sandboxLayers().begin(), sandboxLayers().end(), "memory cgroup") == sandboxLayers().end())
        GTEST_SKIP() << "no memory cgroup here (not root, no delegation)";
    const std::string attack =
        "    std::puts(\"HOSTILE-RAN\");\n    std::fflush(stdout);\n"
        "    int fd = (int)syscall(SYS_memfd_create, \"hostile\", 0);\n"
        "    static char chunk[1 << 20];\n    std::memset(chunk, 1, sizeof chunk);\n"
        "    long held = 0;\n    while (held < 3000 && write(fd, chunk, sizeof chunk) == (ssize_t)sizeof chunk) ++held;\n"
        "    std::printf(\"HELD %ld MiB\\n\", held);\n"
        "    for (int i = 0; i < 6; ++i) if (fork() == 0) {\n"
        "        char* p = (char*)std::malloc(700u << 20); for (long b = 0; p && b < (700l << 20); b += 4096) p[b] = 1;\n"
        "        std::puts(\"CHILD HELD 700 MiB\"); std::fflush(stdout); pause(); }\n"
        "    sleep(5);\n";
    fs::path sub = submissionWith("memory", "texslice3d", "assignments");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp") << hostileCpp(attack, "#include <sys/syscall.h>\n");
    const json s = gradeAndCheck(sub, "texslice3d", "", false, std::size_t(1024) << 20);
    EXPECT_EQ(s["score"].get<double>(), 0.0);
    EXPECT_NE(report_.find("HOSTILE-RAN"), std::string::npos) << s["message"];
    EXPECT_EQ(report_.find("HELD 3000 MiB"), std::string::npos) << "a memfd held 3 GB under a 1 GiB cap";
    std::size_t children = 0;
    for (std::size_t at = report_.find("CHILD HELD"); at != std::string::npos; at = report_.find("CHILD HELD", at + 1))
        ++children;
    EXPECT_LT(children, 4u) << "children held more than the stage's cap together";
}

// --- A class survives any one submission. ---

TEST_F(HostileSubmissions, BatchGradingSurvivesAHostileSubmission) {
    const fs::path classDir = scratch("class");
    for (const char* name : {"alice", "mallory", "zoe"}) fs::create_directories(classDir / name);
    fs::copy(kSource / "reference/texslice3d", classDir / "alice/texslice3d", fs::copy_options::recursive);
    fs::copy(kSource / "assignments/texslice3d", classDir / "mallory/texslice3d", fs::copy_options::recursive);
    std::ofstream(classDir / "mallory/texslice3d/proxy_geometry.cpp")
        << hostileCpp("    kill(-1, SIGKILL);\n    kill(0, SIGKILL);\n");
    fs::copy(kSource / "assignments/texslice3d", classDir / "zoe/texslice3d", fs::copy_options::recursive);
    if (std::find(sandboxLayers().begin(), sandboxLayers().end(), "pid, network and ipc namespaces") ==
        sandboxLayers().end())
        GTEST_SKIP() << "no PID namespace here: kill(-1) would reach this machine's processes";
    GraderOptions o = options();
    o.stages = {"texslice3d"};
    std::vector<Submission> subs;
    for (const char* name : {"alice", "mallory", "zoe"})
        subs.push_back({name, (classDir / name).string(), (classDir / "reports" / name).string()});
    const std::vector<json> reports = gradeSubmissions(subs, o);
    ASSERT_EQ(reports.size(), 3u);
    EXPECT_DOUBLE_EQ(reports[0]["score"].get<double>(), 10.0) << reports[0].dump(1);
    EXPECT_EQ(reports[1]["score"].get<double>(), 0.0);
    EXPECT_NE(reports[1]["stages"][0]["status"], "passed");
    EXPECT_EQ(reports[2]["score"].get<double>(), 0.0);
    for (const char* name : {"alice", "mallory", "zoe"})
        EXPECT_TRUE(fs::exists(classDir / "reports" / name / "report.json")) << name;
}

}  // namespace
}  // namespace voxlab::testing
