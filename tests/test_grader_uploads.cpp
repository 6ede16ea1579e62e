// Uploads of any shape (voxlab/upload.h) and a batch that never stops
// (issue 32 and the zip part of issue 35): an upload is copied once into a
// folder the grader owns, without following a link and within caps; zips
// are unpacked by voxlab with links, absolute names, "..", bombs and too
// many entries refused; a class of bad uploads is graded to the end with a
// gradebook row each and reports that are valid UTF-8; a zip grades as its
// folder does; and swapping the upload while it is graded changes nothing.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>

#include "support/expected_outputs.h"
#include "support/run_command.h"
#include "voxlab/grader.h"
#include "voxlab/untrusted_text.h"
#include "voxlab/upload.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSource = VOXLAB_SOURCE_DIR;

fs::path scratchRoot() { return fs::path(::testing::TempDir()) / ("voxlab_uploads_" + std::to_string(getpid())); }

fs::path scratch(const std::string& name) {
    const fs::path dir = scratchRoot() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void writeBytes(const fs::path& path, const std::string& bytes) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
}

// Every file under `root` (links and all), relative, sorted.
std::vector<std::string> listing(const fs::path& root) {
    std::vector<std::string> out;
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it)
        out.push_back(fs::relative(it->path(), root).string() + (it->is_symlink() ? "@" : it->is_directory() ? "/" : ""));
    std::sort(out.begin(), out.end());
    return out;
}

// Writes a zip with Python's zipfile. Each entry: "NAME" (a small file),
// "NAME/" (a folder), "NAME->TARGET" (a symbolic link), "NAME=N" (N zero bytes).
void makeZip(const fs::path& zip, const std::vector<std::string>& entries) {
    const fs::path script = zip.string() + ".py", list = zip.string() + ".list";
    std::string names;
    for (const std::string& e : entries) names += e + "\n";
    writeBytes(list, names);
    writeBytes(script,
               "import sys, zipfile\n"
               "with zipfile.ZipFile(sys.argv[1], 'w', zipfile.ZIP_DEFLATED) as z:\n"
               "    for e in open(sys.argv[2], encoding='utf-8').read().split('\\n'):\n"
               "        if not e: continue\n"
               "        if '->' in e:\n"
               "            name, target = e.split('->')\n"
               "            info = zipfile.ZipInfo(name)\n"
               "            info.external_attr = (0o120777 << 16)\n"
               "            z.writestr(info, target)\n"
               "        elif '=' in e:\n"
               "            name, n = e.split('=')\n"
               "            z.writestr(name, bytes(int(n)))\n"
               "        else:\n"
               "            z.writestr(e, '' if e.endswith('/') else 'text of ' + e)\n");
    const CommandResult r = runShell("/usr/bin/python3 " + script.string() + " " + zip.string() + " " + list.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    fs::remove(script);
    fs::remove(list);
}

// Zips `folder`'s contents (paths relative to it) with Python's zipfile.
void zipFolder(const fs::path& folder, const fs::path& zip) {
    const CommandResult r = runShell(
        "/usr/bin/python3 -c 'import os, sys, zipfile\n"
        "with zipfile.ZipFile(sys.argv[2], \"w\", zipfile.ZIP_DEFLATED) as z:\n"
        "    for d, _, fs in os.walk(sys.argv[1]):\n"
        "        for f in fs: p = os.path.join(d, f); z.write(p, os.path.relpath(p, sys.argv[1]))' " +
        folder.string() + " " + zip.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
}

TEST(UploadCopy, ZipAttacksAreRefusedWithAReasonAndWriteNothingOutside) {
    const fs::path root = scratch("zip_attacks");
    UploadLimits few;
    few.maxEntries = 10;
    struct Attack {
        std::vector<std::string> entries;
        std::string reason;
        UploadLimits limits;
    };
    const std::vector<Attack> attacks = {
        {{"mip/mip.glsl", "mip/link.glsl->/etc/passwd"}, "'mip/link.glsl' is a link: refused", {}},
        {{"mip/mip.glsl", "../evil"}, "'../evil' climbs out of its folder with '..': refused", {}},
        {{"mip/../../evil"}, "'mip/../../evil' climbs out of its folder with '..': refused", {}},
        {{"/tmp/evil"}, "'/tmp/evil' is an absolute path: refused", {}},
        {{"C:\\evil"}, "'C:/evil' is an absolute path: refused", {}},
        {{"mip/mip.glsl", "bomb=15000000"}, "unpacks to more than 100 times its own size", {}},
        {{"a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k"}, "more than 10 files and folders", few},
    };
    for (std::size_t i = 0; i < attacks.size(); ++i) {
        const fs::path zip = root / ("attack" + std::to_string(i) + ".zip"), into = root / ("into" + std::to_string(i));
        makeZip(zip, attacks[i].entries);
        const std::vector<std::string> before = listing(root);
        const UploadCopy copy = copyUpload(zip.string(), into.string(), attacks[i].limits);
        EXPECT_NE(copy.problem.find(attacks[i].reason), std::string::npos) << i << ": " << copy.problem;
        EXPECT_EQ(copy.problem.find('\n'), std::string::npos) << copy.problem;
        EXPECT_TRUE(fs::is_directory(into) && fs::is_empty(into)) << i;  // what was unpacked before is gone
        std::vector<std::string> after = listing(root);
        after.erase(std::remove(after.begin(), after.end(), into.filename().string() + "/"), after.end());
        EXPECT_EQ(after, before) << i;
    }
    EXPECT_FALSE(fs::exists("/tmp/evil"));
    EXPECT_FALSE(fs::exists(root.parent_path() / "evil"));
}

TEST(UploadCopy, AZipIsUnpackedWithSafeNamesAndAFolderHoldingOnlyAZipIsThatZip) {
    const fs::path root = scratch("zip_good");
    makeZip(root / "alice" / "upload.zip",
            {"voxlab-student/", "voxlab-student/assignments/mip/mip.glsl", "win\\mip\\mip.glsl", "./dot/./x.glsl",
             "__MACOSX/._mip.glsl", "voxlab-student/.git/config", "caf\xc3\xa9/notes.txt", "big=3000000"});
    writeBytes(root / "alice" / ".DS_Store", "finder");
    UploadLimits limits;
    limits.maxFileBytes = 2000000;
    const UploadCopy copy = copyUpload((root / "alice").string(), (root / "copy").string(), limits);
    EXPECT_EQ(copy.problem, "");
    EXPECT_EQ(listing(root / "copy"),
              (std::vector<std::string>{"caf\xc3\xa9/", "caf\xc3\xa9/notes.txt", "dot/", "dot/x.glsl", "voxlab-student/",
                                        "voxlab-student/assignments/", "voxlab-student/assignments/mip/",
                                        "voxlab-student/assignments/mip/mip.glsl", "win/", "win/mip/",
                                        "win/mip/mip.glsl"}));
    EXPECT_EQ(readFile((root / "copy/win/mip/mip.glsl").string()), "text of win\\mip\\mip.glsl");
    ASSERT_EQ(copy.leftOut.size(), 1u);
    EXPECT_EQ(copy.leftOut[0], "big (2.9 MiB, over the 1.9 MiB a file)");
    // Not a zip at all.
    writeBytes(root / "bad.zip", "PK but not really");
    EXPECT_NE(copyUpload((root / "bad.zip").string(), (root / "bad").string()).problem.find("not a zip that can be read"),
              std::string::npos);
}

TEST(UploadCopy, AFolderIsCopiedWithoutFollowingLinksWithinItsCaps) {
    const fs::path root = scratch("folder");
    const fs::path up = root / "up";
    writeBytes(up / "mip/mip.glsl", "float mip_ray();");
    writeBytes(up / "deep/1/2/3/4/x.glsl", "deep");
    writeBytes(up / "large.raw", std::string(5000, 'x'));
    writeBytes(up / ".git/objects/ab", "hidden");
    fs::create_symlink("/etc/passwd", up / "mip/passwd.glsl");
    fs::create_directory_symlink(kSource / "reference", up / "reference");
    ASSERT_EQ(mkfifo((up / "mip/fifo.glsl").c_str(), 0600), 0);
    UploadLimits limits;
    limits.maxDepth = 3;
    limits.maxFileBytes = 4096;
    const UploadCopy copy = copyUpload(up.string(), (root / "copy").string(), limits);
    EXPECT_EQ(copy.problem, "");
    EXPECT_EQ(listing(root / "copy"), (std::vector<std::string>{"deep/", "deep/1/", "deep/1/2/", "mip/", "mip/mip.glsl"}));
    EXPECT_EQ(copy.leftOut, (std::vector<std::string>{"deep/1/2/3 (deeper than 3 folders)",
                                                      "large.raw (5000 bytes, over the 4 KiB a file)",
                                                      "mip/fifo.glsl (not a regular file)", "mip/passwd.glsl (a link)",
                                                      "reference (a link)"}));
    limits = UploadLimits();
    limits.maxTotalBytes = 4000;
    EXPECT_EQ(copyUpload(up.string(), (root / "copy2").string(), limits).problem,
              "the upload holds more than 4000 bytes (the limit)");
    limits = UploadLimits();
    limits.maxEntries = 5;
    EXPECT_EQ(copyUpload(up.string(), (root / "copy3").string(), limits).problem,
              "the upload holds more than 5 files and folders (the limit)");
    EXPECT_EQ(copyUpload((root / "nowhere").string(), (root / "copy4").string()).problem,
              "the upload cannot be read: No such file or directory");
}

// The grading tests: the reference's expected outputs for mip and the C++
// stage texslice3d, rendered once.
class Uploads : public ExpectedOutputsSuite<Uploads> {
public:
    static fs::path expectedFolder() { return scratch("expected"); }
    static void TearDownTestSuite() { fs::remove_all(scratchRoot()); }
    static GraderOptions options() {
        GraderOptions o = referenceOptions();
        o.jobs = 2;
        o.stages = {"mip", "texslice3d"};
        return o;
    }
};

std::string referenceMip() { return readFile((kSource / "reference/mip/mip.glsl").string()); }

// A mip stage file with `line` inserted after its first line.
std::string mipWith(const std::string& line) {
    std::string text = referenceMip();
    return text.insert(text.find('\n') + 1, line + "\n");
}

// The class of bad uploads of the issue, in `batch`.
void makeBadClass(const fs::path& batch) {
    const fs::path root = batch.parent_path();
    writeBytes(batch / "alice/mip/mip.glsl", referenceMip());
    writeBytes(root / "bob/mip/mip.glsl", referenceMip());
    zipFolder(root / "bob", batch / "bob.zip");  // a zip in the class folder itself
    writeBytes(root / "carol/voxlab-student/assignments/mip/mip.glsl", referenceMip());
    fs::create_directories(batch / "carol");
    zipFolder(root / "carol", batch / "carol/submission.zip");  // a folder holding only a zip
    writeBytes(batch / "dave/notes.txt", "I did not finish");
    writeBytes(batch / "gradebook.csv/mip/mip.glsl", referenceMip());
    writeBytes(batch / "l\xe9" "a/sub\xe9/mip/mip.glsl", referenceMip());  // Latin-1 folder names
    fs::create_directories(batch / "empty");
    writeBytes(batch / "erin/mip/mip.glsl", mipWith("#error caf\xe9 \x1b[2J\x1b]0;owned\x07 =HYPERLINK(\"http://x\")"));
    writeBytes(batch / "frank/mip/mip.glsl", mipWith(std::string(200000, ' ')));
    writeBytes(batch / "\x1b[31m=HYPERLINK(\"http:x\")/mip/mip.glsl", referenceMip());
    const std::string cpp = readFile((kSource / "reference/texslice3d/proxy_geometry.cpp").string());
    writeBytes(batch / "gina/texslice3d/proxy_geometry.cpp", "#error na\xefve\n" + cpp);
    writeBytes(batch / "hank/texslice3d/proxy_geometry.cpp",
               cpp + "\n#include <cstdlib>\nnamespace { const int boom = (std::abort(), 0); }\n");
    makeZip(batch / "ivan.zip", {"mip/mip.glsl", "../evil"});
}

const json& stageOf(const json& report, const std::string& id) {
    for (const json& s : report["stages"])
        if (s["stage"] == id) return s;
    static const json none;
    return none;
}

TEST_F(Uploads, AClassOfBadUploadsIsGradedToTheEndWithARowEach) {
    const fs::path root = scratch("bad_class"), batch = root / "class", out = root / "reports";
    makeBadClass(batch);
    const CommandResult r = runVoxlab("grade --batch " + batch.string() + " --stage mip --stage texslice3d --out " +
                                          out.string() + " --jobs 2 --quiet --similarity-threshold 0.5",
                                      600);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
    EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
    const std::string csv = readFile((out / "gradebook.csv").string());
    EXPECT_TRUE(isValidUtf8(csv));
    EXPECT_EQ(lineCount(csv), 1 + 13) << csv;  // the header and a row per upload
    for (std::size_t at = 0; at != std::string::npos; at = csv.find_first_of(",\n", at + 1))
        EXPECT_NE(csv[at + 1 < csv.size() ? at + 1 : at], '=') << csv;
    EXPECT_NE(csv.find("\"'=HYPERLINK(\"\"http:x\"\")\",10.00,20.00,10.00,0.00,"), std::string::npos) << csv;
    for (const std::string& file : {"index.html", "gradebook.csv", "similarity.html", "similarity.json"})
        EXPECT_TRUE(isValidUtf8(readFile((out / file).string()))) << file;

    std::map<std::string, json> reports;
    for (const auto& entry : fs::directory_iterator(out)) {
        if (!entry.is_directory() || entry.path().filename().string()[0] == '.') continue;
        for (const char* file : {"report.json", "results.json", "index.html"})
            EXPECT_TRUE(isValidUtf8(readFile((entry.path() / file).string()))) << entry.path() << "/" << file;
        const json report = json::parse(readFile((entry.path() / "report.json").string()));
        reports[entry.path().filename().string()] = report;
        EXPECT_NE(readFile((out / "index.html").string()).find("href=\"" + entry.path().filename().string() + "/index.html\""),
                  std::string::npos) << entry.path();
    }
    EXPECT_EQ(reports.size(), 13u);
    const double alice = reports["alice"]["score"];
    EXPECT_EQ(alice, 10.0);
    EXPECT_EQ(reports["bob"]["score"], alice);    // a zip in the class folder
    EXPECT_EQ(reports["carol"]["score"], alice);  // a folder holding only a zip of a nested layout
    EXPECT_EQ(reports["gradebook.csv-2"]["name"], "gradebook.csv");
    EXPECT_EQ(reports["gradebook.csv-2"]["score"], alice);
    EXPECT_EQ(reports["l_a"]["name"], "l\xef\xbf\xbd" "a");
    EXPECT_EQ(reports["l_a"]["score"], alice);
    EXPECT_EQ(reports["frank"]["score"], alice);  // a line of 200 000 spaces
    EXPECT_EQ(reports["_31m_HYPERLINK_http_x_"]["score"], alice);
    for (const char* name : {"dave", "empty", "ivan"}) {
        EXPECT_EQ(reports[name]["status"], "error") << name;
        EXPECT_EQ(reports[name]["score"], 0.0) << name;
        EXPECT_EQ(reports[name]["max_score"], 20.0) << name;
        const std::size_t row = csv.find(std::string("\n") + name + ",0.00,20.00,0.00,0.00,");
        ASSERT_NE(row, std::string::npos) << name << "\n" << csv;
        EXPECT_NE(csv.substr(row + 1, csv.find('\n', row + 1) - row).find("not graded: "), std::string::npos) << name;
    }
    EXPECT_NE(reports["dave"]["message"].get<std::string>().find("no stage folder (mip/, texslice3d/)"), std::string::npos);
    EXPECT_NE(reports["ivan"]["message"].get<std::string>().find("climbs out"), std::string::npos);
    EXPECT_EQ(stageOf(reports["erin"], "mip")["status"], "compile_error");
    EXPECT_NE(stageOf(reports["erin"], "mip")["message"].get<std::string>().find("caf\xef\xbf\xbd"), std::string::npos);
    EXPECT_EQ(stageOf(reports["gina"], "texslice3d")["status"], "compile_error");
    EXPECT_EQ(stageOf(reports["hank"], "texslice3d")["status"], "crashed");
    EXPECT_FALSE(fs::exists(root / "evil"));
    EXPECT_FALSE(fs::exists(batch / "evil"));
    std::vector<std::string> leftovers;  // the uploads' copies are gone
    for (const auto& entry : fs::directory_iterator(out))
        if (entry.path().filename().string().rfind(".uploads", 0) == 0) leftovers.push_back(entry.path());
    EXPECT_TRUE(leftovers.empty());
}

TEST_F(Uploads, AZipGradesAsItsFolderAndABadSingleUploadStillGetsItsReport) {
    const fs::path root = scratch("single");
    writeBytes(root / "alice/mip/mip.glsl", mipWith("// a comment"));
    std::string stub = readFile((kSource / "assignments/mip/mip.glsl").string());
    writeBytes(root / "alice/minip/minip.glsl", readFile((kSource / "reference/minip/minip.glsl").string()));
    zipFolder(root / "alice", root / "alice.zip");
    const auto grade = [&](const std::string& upload, const std::string& out) {
        const CommandResult r = runVoxlab("grade --submission " + (root / upload).string() +
                                              " --stage mip --stage minip --out " + (root / out).string() + " --quiet",
                                          300);
        json report = json::parse(readFile((root / out / "report.json").string()));
        report["exit"] = r.exitCode;
        return report;
    };
    const json folder = grade("alice", "out_folder"), zip = grade("alice.zip", "out_zip");
    EXPECT_EQ(folder["exit"], 0);
    EXPECT_EQ(zip["exit"], 0);
    EXPECT_EQ(zip["name"], "alice");
    ASSERT_EQ(zip["stages"].size(), folder["stages"].size());
    for (std::size_t i = 0; i < zip["stages"].size(); ++i)
        for (const char* key : {"stage", "status", "score", "message", "scenes", "checks"})
            EXPECT_EQ(zip["stages"][i][key], folder["stages"][i][key]) << i << " " << key;
    EXPECT_EQ(zip["score"], folder["score"]);

    writeBytes(root / "dave/notes.txt", "nothing");
    const json dave = grade("dave", "out_dave");
    EXPECT_EQ(dave["exit"], 1);
    EXPECT_EQ(dave["status"], "error");
    EXPECT_TRUE(fs::exists(root / "out_dave/index.html"));
    const json results = json::parse(readFile((root / "out_dave/results.json").string()));
    EXPECT_NE(results["output"].get<std::string>().find("Not graded: no stage folder"), std::string::npos);
    EXPECT_EQ(runVoxlab("grade --submission " + (root / "nowhere.zip").string()).err,
              "voxlab: " + (root / "nowhere.zip").string() + ": no such folder or .zip file\n");
}

// A thread swaps the upload's stage folder between a correct one and the
// starter code's stub while the class is prepared and graded: the score is
// always what the copy taken at the start earns.
TEST_F(Uploads, SwappingTheUploadWhileItIsGradedNeverChangesWhatItsCopyEarns) {
    const fs::path root = scratch("swap");
    writeBytes(root / "class/alice/mip/mip.glsl", referenceMip());
    writeBytes(root / "spare/mip/mip.glsl", readFile((kSource / "assignments/mip/mip.glsl").string()));
    const fs::path live = root / "class/alice/mip", spare = root / "spare/mip";
    std::atomic<bool> stop{false};
    std::atomic<long> swaps{0};
    std::thread swapper([&] {
        while (!stop) {
            if (renameat2(AT_FDCWD, live.c_str(), AT_FDCWD, spare.c_str(), RENAME_EXCHANGE) == 0) ++swaps;
            std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
    });
    GraderOptions o = options();
    o.stages = {"mip"};
    int correct = 0, stubbed = 0;
    for (int round = 0; round < 6; ++round) {
        const fs::path copy = root / ("copy" + std::to_string(round));
        const Submission s = prepareSubmission("alice", (root / "class/alice").string(),
                                               (root / ("report" + std::to_string(round))).string(), copy.string(), o);
        ASSERT_EQ(s.problem, "");
        const bool isCorrect = readFile((copy / "mip/mip.glsl").string()) == referenceMip();
        (isCorrect ? correct : stubbed) += 1;
        const json report = gradeSubmissions({s}, o).at(0);
        EXPECT_EQ(report["score"].get<double>(), isCorrect ? 10.0 : 0.0) << "round " << round;
        EXPECT_EQ(report["stages"][0]["status"], isCorrect ? "passed" : "not_implemented") << "round " << round;
    }
    stop = true;
    swapper.join();
    EXPECT_GT(swaps.load(), 100);
    std::cout << "[          ] " << swaps << " swaps; the copy held the correct stage " << correct
              << " times, the stub " << stubbed << " times\n";
}

}  // namespace
}  // namespace voxlab::testing
