#pragma once
// voxlab: numbers as text, the one place that says how. Shortest text that
// reads back as the same value, and strict parsing (the whole text is one
// number, no spaces, no hexadecimal). Natively these are <charconv>'s
// to_chars/from_chars; the browser build's C++ library (emscripten 3.1.6's
// libc++) has them only for integers, so there the same contract is kept
// with printf/strtod.

#include <string>

namespace voxlab {

std::string shortestText(double value);
std::string shortestText(float value);
// True when [first, last) is exactly one decimal number (a leading '+' is the
// caller's to strip); the value goes to *out.
bool parseDoubleExactly(const char* first, const char* last, double* out);

}  // namespace voxlab
