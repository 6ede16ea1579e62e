// voxlab fuzzing: what every libFuzzer target in tests/fuzz/ shares.
//
// The targets feed arbitrary bytes to voxlab's parsers, through the same
// entry points the command line uses (loadNrrd, Scene::load, ...). Because
// those entry points read files, each process gets a private scratch folder
// (under $TMPDIR, removed at exit) and every input is written there first.
//
// The contract under test (README, "bad input gives a clear one-line
// voxlab::Error"): for any bytes, a parser either succeeds or throws
// voxlab::Error whose message is one non-empty line. Everything else is a
// finding, and each is made to stop libFuzzer with a crash report:
//  - another exception type (nlohmann::json::type_error, std::bad_alloc,
//    std::filesystem::filesystem_error, ...): printed, then abort();
//  - an Error message that is empty or spans lines: printed, then abort();
//  - a sanitizer report (AddressSanitizer, UndefinedBehaviorSanitizer, built
//    with -fno-sanitize-recover so the first one stops the run);
//  - an input that runs longer than -timeout or allocates more than
//    -malloc_limit_mb / -rss_limit_mb (libFuzzer's own checks).
//
// Formats made of two files (a detached NRRD header and its data, a .dat
// and its .raw) take one fuzzer input holding both, split at the first
// kDataSeparator: header before it, data after it (no separator: no data).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <fstream>
#include <string>
#include <string_view>
#include <typeinfo>
#include <unistd.h>

#include "voxlab/error.h"

namespace voxlab::fuzz {

// Between the header part and the data part of a two-file input.
inline constexpr std::string_view kDataSeparator = "\n--voxlab-fuzz-data--\n";

struct TwoFiles {
    std::string header;
    std::string data;
};

inline TwoFiles splitInput(const std::uint8_t* bytes, std::size_t size) {
    std::string_view all(reinterpret_cast<const char*>(bytes), size);
    const std::size_t at = all.find(kDataSeparator);
    if (at == std::string_view::npos) return {std::string(all), std::string()};
    return {std::string(all.substr(0, at)), std::string(all.substr(at + kDataSeparator.size()))};
}

// This process's scratch folder, created on first use and removed at exit.
inline const std::string& scratchDir() {
    static const std::string dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/voxlab_fuzz_XXXXXX";
        if (!mkdtemp(pattern.data())) {
            std::perror("voxlab fuzz: mkdtemp");
            std::abort();
        }
        static const std::string removeAtExit = pattern;
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(removeAtExit, ec);
        });
        return pattern;
    }();
    return dir;
}

inline std::string scratchFile(const std::string& name) { return scratchDir() + "/" + name; }

// Writes (replaces) a scratch file; a failure here is the harness's, not a finding.
inline void writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
        std::fprintf(stderr, "voxlab fuzz: cannot write %s\n", path.c_str());
        std::abort();
    }
}

[[noreturn]] inline void finding(const char* what, const std::string& detail) {
    std::fprintf(stderr, "\nvoxlab fuzz finding: %s\n  %s\n", what, detail.c_str());
    std::fflush(stderr);
    std::abort();
}

// A voxlab::Error's message must be one non-empty line.
inline void checkMessage(const Error& e) {
    const std::string message = e.what();
    if (message.empty()) finding("voxlab::Error with an empty message", "");
    if (message.find_first_of("\n") != std::string::npos)
        finding("voxlab::Error message spans several lines", message);
}

// The harness's self-test (CTest: fuzz_NAME_canary): with
// VOXLAB_FUZZ_CANARY=1 every parse first throws std::logic_error, a stand-in
// for a parser bug, which must end the run as a finding.
inline void canary() {
    static const bool planted = [] {
        const char* v = std::getenv("VOXLAB_FUZZ_CANARY");
        return v && std::string(v) == "1";
    }();
    if (planted) throw std::logic_error("planted by VOXLAB_FUZZ_CANARY=1");
}

// Runs `parse`: success and a well-formed voxlab::Error are both fine.
template <class F>
void expectOnlyVoxlabErrors(F parse) {
    try {
        canary();
        parse();
    } catch (const Error& e) {
        checkMessage(e);
    } catch (const std::exception& e) {
        finding("exception other than voxlab::Error",
                std::string(typeid(e).name()) + ": " + e.what());
    } catch (...) {
        finding("exception other than voxlab::Error", "(not a std::exception)");
    }
}

// A property the parsed result must have (e.g. a round trip); stops the run.
inline void require(bool ok, const char* what, const std::string& detail = "") {
    if (!ok) finding(what, detail);
}

}  // namespace voxlab::fuzz
