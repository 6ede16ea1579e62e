// Every file voxlab saves goes through writeFileAtomically: a failed save
// says so on one line naming the file, leaves the old file byte for byte,
// replaces a symbolic link instead of writing through it, and leaves no
// temporary files behind. Each case runs over every saver in the framework.
//
// Failures are provoked in ways that also work as root (the tests run as
// root, where permission bits stop nothing): /dev/full (ENOSPC on write), a
// file-size limit (RLIMIT_FSIZE, EFBIG) set in a forked child, a missing
// folder and a folder at the target.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/error_of.h"
#include "support/in_child.h"
#include "support/temp_dir.h"
#include "voxlab/atomic_file.h"
#include "voxlab/error.h"
#include "voxlab/html_report.h"
#include "voxlab/image.h"
#include "voxlab/transfer_function.h"
#include "voxlab/transfer_function_2d.h"
#include "voxlab/volume.h"
#ifdef VOXLAB_HAVE_VIEWER
#include "voxlab/transfer_function_editor.h"
#endif

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

void writeBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// Names in a folder, dot files (the temporary files) included.
std::set<std::string> listFolder(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

// Pseudo-random pixels and voxels: they compress badly, so every saver's
// output is several kilobytes.
Image noiseImage(int w, int h) {
    Image img(w, h);
    std::uint32_t state = 99;
    for (float& v : img.rgba) {
        state = state * 1664525u + 1013904223u;
        v = float(state >> 24) / 255.0f;
    }
    return img;
}

Volume noiseVolume(int n) {
    std::vector<std::uint8_t> bytes(std::size_t(n) * n * n);
    std::uint32_t state = 7;
    for (auto& b : bytes) {
        state = state * 1664525u + 1013904223u;
        b = std::uint8_t(state >> 24);
    }
    return Volume(glm::ivec3(n), VoxelType::UInt8, glm::dvec3(1.0), std::move(bytes), "noise");
}

TransferFunction manyPoints() {
    std::vector<ControlPoint> points;
    for (int i = 0; i < 64; ++i) points.push_back({double(i), glm::vec3(0.25f, 0.5f, 0.75f), 0.5f});
    return TransferFunction(points);
}

// One way of saving a file. `save` writes the file at `target`; savers that
// choose their own file name (the HTML reports write FOLDER/index.html)
// name it in `fixedName` and cannot be aimed at a device.
struct Saver {
    std::string name;
    std::string fixedName;
    std::function<void(const std::string& target)> save;
};

std::vector<Saver> allSavers() {
    std::vector<Saver> savers = {
        {"writeFileAtomically", "", [](const std::string& p) { writeFileAtomically(p, std::string(5000, 'x')); }},
        {"savePng", "", [](const std::string& p) { savePng(noiseImage(40, 30), p); }},
        {"saveNrrd raw", "", [](const std::string& p) { saveNrrd(noiseVolume(16), p, false); }},
        {"saveNrrd gzip", "", [](const std::string& p) { saveNrrd(noiseVolume(16), p, true); }},
        {"writeClassHtmlReport", "index.html",
         [](const std::string& p) {
             writeClassHtmlReport(nlohmann::json::array({{{"name", "alice"}}, {{"name", "bob"}}}),
                                  fs::path(p).parent_path().string());
         }},
    };
#ifdef VOXLAB_HAVE_VIEWER
    // The editors' save buttons: they report failures in a message.
    savers.push_back({"saveTransferFunctionFile 1D", "", [](const std::string& p) {
                          std::string message;
                          if (!saveTransferFunctionFile(p, manyPoints(), &message)) throw Error(message);
                      }});
    savers.push_back({"saveTransferFunctionFile 2D", "", [](const std::string& p) {
                          Tf2dWidget w;
                          w.valueRange = glm::dvec2(10.0);
                          w.radius = 1.5;
                          w.alpha = 0.5f;
                          std::string message;
                          if (!saveTransferFunctionFile(p, TransferFunction2D(std::vector<Tf2dWidget>(kMaxTf2dWidgets, w)), &message))
                              throw Error(message);
                      }});
#endif
    return savers;
}

class AtomicWrites : public ::testing::Test {
protected:
    // A fresh folder per saver, so that listings show only its own files.
    fs::path folderFor(const Saver& s) const {
        fs::path d = dir_ / std::to_string(std::hash<std::string>()(s.name));
        fs::create_directories(d);
        return d;
    }
    static std::string fileName(const Saver& s) { return s.fixedName.empty() ? "out.dat" : s.fixedName; }
    TempDir tmp_{"voxlab-atomic"};
    const fs::path dir_ = tmp_.path();
};

// The message of the voxlab::Error thrown by `f` in a forked child whose
// files may not grow past `limitBytes`. SIGXFSZ is ignored there, so an
// oversized write fails with EFBIG instead of killing the child. Returns
// "no error" when nothing is thrown (messageInChild says the rest).
std::string errorUnderFileSizeLimit(const std::function<void()>& f, rlim_t limitBytes) {
    return messageInChild(
        [&] {
            std::signal(SIGXFSZ, SIG_IGN);
            const struct rlimit limit = {limitBytes, limitBytes};
            return ::setrlimit(RLIMIT_FSIZE, &limit) == 0;
        },
        [&] {
            f();
            return std::string("no error");
        });
}

TEST_F(AtomicWrites, SuccessWritesTheFileAndNoTemporaries) {
    for (const Saver& s : allSavers()) {
        const fs::path folder = folderFor(s), target = folder / fileName(s);
        ASSERT_NO_THROW(s.save(target.string())) << s.name;
        EXPECT_EQ(listFolder(folder), std::set<std::string>{fileName(s)}) << s.name;
        EXPECT_GT(fs::file_size(target), 1000u) << s.name;
        // Readable by all, like a file made with the usual umask (mkstemp
        // alone would leave 0600).
        EXPECT_EQ(fs::status(target).permissions() & fs::perms::all,
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read)
            << s.name;
    }
    // The contents, read back by independent means where the format allows.
    const fs::path raw = dir_ / "raw.bin";
    writeFileAtomically(raw.string(), std::string("a\0b", 3));
    EXPECT_EQ(readText(raw), std::string("a\0b", 3));
    const Image img = noiseImage(40, 30);
    savePng(img, (dir_ / "img.png").string());
    const Image back = loadPng((dir_ / "img.png").string());
    ASSERT_EQ(back.width, 40);
    for (std::size_t i = 0; i < img.rgba.size(); ++i)
        if (i % 4 != 3) ASSERT_EQ(toByte(back.rgba[i]), toByte(img.rgba[i])) << i;
    const Volume v = noiseVolume(16);
    saveNrrd(v, (dir_ / "v.nrrd").string(), false);
    EXPECT_EQ(readText(dir_ / "v.nrrd").substr(readText(dir_ / "v.nrrd").size() - v.bytes().size()),
              std::string(v.bytes().begin(), v.bytes().end()));
}

TEST_F(AtomicWrites, DevFullFailsWithOneLineNamingIt) {
    for (const Saver& s : allSavers()) {
        if (!s.fixedName.empty()) continue;
        const std::string message = errorOf([&] { s.save("/dev/full"); });
        EXPECT_NE(message.find("/dev/full"), std::string::npos) << s.name << ": " << message;
        EXPECT_NE(message.find("No space left on device"), std::string::npos) << s.name << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << s.name << ": " << message;
    }
}

TEST_F(AtomicWrites, DevicesAreWrittenInPlaceNotReplaced) {
    ASSERT_NO_THROW(writeFileAtomically("/dev/null", "discarded"));
    struct stat st {};
    ASSERT_EQ(::lstat("/dev/null", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/null was replaced";
}

TEST_F(AtomicWrites, FailedWriteLeavesTheOldFileByteIdentical) {
    const std::string old = "the previous file\n" + std::string(300, 'o');
    for (const Saver& s : allSavers()) {
        const fs::path folder = folderFor(s), target = folder / fileName(s);
        writeBytes(target, old);
        // 1000 bytes: more than the old file, less than any saver writes.
        const std::string message = errorUnderFileSizeLimit([&] { s.save(target.string()); }, 1000);
        EXPECT_NE(message.find(target.string()), std::string::npos) << s.name << ": " << message;
        EXPECT_NE(message.find("File too large"), std::string::npos) << s.name << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << s.name << ": " << message;
        EXPECT_EQ(readText(target), old) << s.name;
        EXPECT_EQ(listFolder(folder), std::set<std::string>{fileName(s)}) << s.name << ": a temporary file is left";
    }
}

TEST_F(AtomicWrites, MissingFolderAndFolderTargetsFailWithoutLeftovers) {
    for (const Saver& s : allSavers()) {
        const fs::path folder = folderFor(s);
        if (s.fixedName.empty()) {
            const fs::path missing = folder / "no" / "such" / "folder" / "out.dat";
            const std::string message = errorOf([&] { s.save(missing.string()); });
            EXPECT_NE(message.find(missing.string()), std::string::npos) << s.name << ": " << message;
            EXPECT_FALSE(fs::exists(folder / "no")) << s.name;
        }
        // A folder where the file should be: refused, and the folder and
        // what it holds are untouched.
        const fs::path target = folder / fileName(s);
        fs::create_directories(target);
        writeBytes(target / "inside", "kept");
        const std::string message = errorOf([&] { s.save(target.string()); });
        EXPECT_NE(message.find(target.string()), std::string::npos) << s.name << ": " << message;
        EXPECT_TRUE(fs::is_directory(target)) << s.name;
        EXPECT_EQ(readText(target / "inside"), "kept") << s.name;
        EXPECT_EQ(listFolder(folder), std::set<std::string>{fileName(s)}) << s.name << ": a temporary file is left";
    }
}

TEST_F(AtomicWrites, SymbolicLinkAtTheTargetIsReplacedNotFollowed) {
    for (const Saver& s : allSavers()) {
        const fs::path folder = folderFor(s), target = folder / fileName(s);
        const fs::path victim = dir_ / ("victim-" + std::to_string(std::hash<std::string>()(s.name)));
        writeBytes(victim, "must not change");
        fs::create_symlink(victim, target);
        ASSERT_NO_THROW(s.save(target.string())) << s.name;
        EXPECT_EQ(readText(victim), "must not change") << s.name;
        EXPECT_FALSE(fs::is_symlink(target)) << s.name;
        EXPECT_TRUE(fs::is_regular_file(target)) << s.name;
        EXPECT_GT(fs::file_size(target), 1000u) << s.name;
        EXPECT_EQ(listFolder(folder), std::set<std::string>{fileName(s)}) << s.name;
    }
    // A dangling link: the save makes a file at the link, none where it pointed.
    const fs::path dangling = dir_ / "dangling.png", nowhere = dir_ / "nowhere.png";
    fs::create_symlink(nowhere, dangling);
    savePng(noiseImage(4, 4), dangling.string());
    EXPECT_FALSE(fs::exists(nowhere));
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dangling)));
}

}  // namespace
}  // namespace voxlab::testing
