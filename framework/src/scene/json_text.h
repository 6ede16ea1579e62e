// voxlab: small text helpers shared by the JSON readers and writers
// (scene.cpp, transfer_function.cpp).
#pragma once

#include <string>

namespace voxlab::json_text {

// A float written as the shortest decimal that reads back as the same float
// (0.1f is written 0.1, not 0.10000000149011612).
double shortFloat(float f);

// nlohmann's messages without their "[json.exception...] " tag, on one line.
std::string oneLine(std::string msg);

}  // namespace voxlab::json_text
