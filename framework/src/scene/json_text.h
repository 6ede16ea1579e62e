// voxlab: small helpers shared by the JSON readers and writers
// (scene.cpp, transfer_function.cpp).
#pragma once

#include <cstddef>
#include <istream>
#include <string>

#include <nlohmann/json.hpp>

#include "voxlab/error.h"

namespace voxlab::json_text {

// A float written as the shortest decimal that reads back as the same float
// (0.1f is written 0.1, not 0.10000000149011612).
double shortFloat(float f);

// nlohmann's messages without their "[json.exception...] " tag, on one line.
std::string oneLine(std::string msg);

// The largest text input read whole (scenes, transfer functions, grading
// manifests, viewer scripts): 16 MiB. A parsed JSON document takes up to
// about 30 times its text in memory (measured: 16 MiB of "{}," became 480
// MiB), and the largest real input, a transfer function at its point cap
// written with dump(2), is about 7 MiB.
constexpr std::size_t kMaxTextInputBytes = std::size_t(16) << 20;

// Reads all of `in`, refusing more than kMaxTextInputBytes before holding
// it: "<path>: more than 16 MiB (the limit for a text input)". A regular
// file's size is checked first, so a huge one is refused without reading.
std::string readCappedText(std::istream& in, const std::string& path);

// The message with each control character (U+0000..U+001F, U+007F) written
// as its JSON escape (\n, \t, \u001b): keys and strings from a document are
// echoed as they are written in it, and the message stays on one line.
std::string escapeControls(const std::string& msg);

// Runs `parse`; a voxlab::Error it throws is thrown again through
// escapeControls (the public fromJson functions wrap their parsers in it).
template <class F>
auto escapedErrors(F parse) -> decltype(parse()) {
    try {
        return parse();
    } catch (const Error& e) {
        throw Error(escapeControls(e.what()));
    }
}

// Parses a JSON file; a missing file, one over kMaxTextInputBytes or a
// syntax error becomes one voxlab::Error line that starts with the path.
nlohmann::json readJsonFile(const std::string& path);

}  // namespace voxlab::json_text
