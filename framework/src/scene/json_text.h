// voxlab: small helpers shared by the JSON readers and writers
// (scene.cpp, transfer_function.cpp).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "voxlab/error.h"

namespace voxlab::json_text {

// A float written as the shortest decimal that reads back as the same float
// (0.1f is written 0.1, not 0.10000000149011612).
double shortFloat(float f);

// nlohmann's messages without their "[json.exception...] " tag, on one line.
std::string oneLine(std::string msg);

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

// Parses a JSON file; a missing file or a syntax error becomes one
// voxlab::Error line that starts with the path.
nlohmann::json readJsonFile(const std::string& path);

}  // namespace voxlab::json_text
