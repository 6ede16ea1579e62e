// voxlab: numbers as text (see number_text.h).
#include "voxlab/number_text.h"

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <system_error>

namespace voxlab {

#ifndef __EMSCRIPTEN__

template <class T>
static std::string shortest(T value) {
    char buf[64];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);
    return ec == std::errc() ? std::string(buf, end) : std::to_string(value);
}

bool parseDoubleExactly(const char* first, const char* last, double* out) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(first, last, value, std::chars_format::general);
    if (ec != std::errc() || end != last) return false;
    *out = value;
    return true;
}

#else

// The fewest significant digits (up to the type's round-trip count: 9 for
// float, 17 for double) whose %g text reads back as the same value.
template <class T>
static std::string shortest(T value) {
    char buf[64];
    for (int digits = 1; digits <= (sizeof(T) == 4 ? 9 : 17); ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, double(value));
        if (T(std::strtod(buf, nullptr)) == value) break;
    }
    return buf;
}

bool parseDoubleExactly(const char* first, const char* last, double* out) {
    const std::string text(first, last);
    // strtod also takes what from_chars refuses: spaces, a sign '+', hex.
    if (text.empty() || std::strchr(" \t\n\r\f\v+xX", text[0]) || text.find_first_of("xXpP") != std::string::npos)
        return false;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size()) return false;
    *out = value;
    return true;
}

#endif

std::string shortestText(double value) { return shortest(value); }
std::string shortestText(float value) { return shortest(value); }

}  // namespace voxlab
