// voxlab: see json_text.h.
#include "json_text.h"

#include <cerrno>
#include <cstdio>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "voxlab/error.h"

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

std::string escapeControls(const std::string& msg) {
    std::string out;
    out.reserve(msg.size());
    for (const char c : msg) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x20 && u != 0x7f) {
            out += c;
        } else if (c == '\n') {
            out += "\\n";
        } else if (c == '\r') {
            out += "\\r";
        } else if (c == '\t') {
            out += "\\t";
        } else {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(u));
            out += buf;
        }
    }
    return out;
}

nlohmann::json readJsonFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open: " + std::strerror(errno));
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path + ": " + oneLine(e.what()));
    }
}

}  // namespace voxlab::json_text
