// voxlab: see json_text.h.
#include "json_text.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "voxlab/error.h"
#include "voxlab/number_text.h"

namespace voxlab::json_text {

double shortFloat(float f) {
    const double d = std::strtod(shortestText(f).c_str(), nullptr);
    return float(d) == f ? d : double(f);
}

std::string oneLine(std::string msg) {
    if (msg.rfind("[json.exception.", 0) == 0 && msg.find("] ") != std::string::npos)
        msg.erase(0, msg.find("] ") + 2);
    for (char& c : msg)
        if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    return msg;
}

std::string readCappedText(std::istream& in, const std::string& path) {
    const std::string tooLarge = path + ": more than " + std::to_string(kMaxTextInputBytes >> 20) +
                                 " MiB (the limit for a text input)";
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);  // fails for pipes and devices: read them
    if (!ec && size > kMaxTextInputBytes) throw Error(tooLarge);
    // Read in chunks up to one byte past the limit: the file may have grown,
    // or not be a regular file at all.
    std::string text;
    char chunk[1 << 16];
    while (in && text.size() <= kMaxTextInputBytes) {
        in.read(chunk, sizeof chunk);
        text.append(chunk, std::size_t(in.gcount()));
    }
    if (text.size() > kMaxTextInputBytes) throw Error(tooLarge);
    if (in.bad()) throw Error(path + ": cannot read");
    return text;
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
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open: " + std::strerror(errno));
    const std::string text = readCappedText(in, path);
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path + ": " + oneLine(e.what()));
    }
}

}  // namespace voxlab::json_text
