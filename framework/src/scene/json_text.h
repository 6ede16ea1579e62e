// voxlab: small helpers shared by the JSON readers and writers
// (scene.cpp, transfer_function.cpp).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace voxlab::json_text {

// A float written as the shortest decimal that reads back as the same float
// (0.1f is written 0.1, not 0.10000000149011612).
double shortFloat(float f);

// nlohmann's messages without their "[json.exception...] " tag, on one line.
std::string oneLine(std::string msg);

// Parses a JSON file; a missing file or a syntax error becomes one
// voxlab::Error line that starts with the path.
nlohmann::json readJsonFile(const std::string& path);

}  // namespace voxlab::json_text
