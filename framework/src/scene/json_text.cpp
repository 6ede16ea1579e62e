// voxlab: see json_text.h.
#include "json_text.h"

#include <charconv>
#include <cstdlib>

namespace voxlab::json_text {

double shortFloat(float f) {
    char buf[32];
    auto res = std::to_chars(buf, buf + sizeof buf, f);
    const double d = std::strtod(std::string(buf, res.ptr).c_str(), nullptr);
    return float(d) == f ? d : double(f);
}

std::string oneLine(std::string msg) {
    if (msg.rfind("[json.exception.", 0) == 0 && msg.find("] ") != std::string::npos)
        msg.erase(0, msg.find("] ") + 2);
    for (char& c : msg)
        if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    return msg;
}

}  // namespace voxlab::json_text
