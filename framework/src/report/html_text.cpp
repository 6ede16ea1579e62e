// voxlab: escaping, optional fields and formatting for the grader's HTML
// reports (they are saved with writeFileAtomically).
#include "html_text.h"

#include "voxlab/untrusted_text.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

namespace voxlab::html {

using nlohmann::json;

std::string escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : safeText(text, std::string::npos)) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string urlPath(std::string_view path) {
    static const char* hex = "0123456789ABCDEF";
    std::string out;
    for (char c : path) {
        const auto byte = static_cast<unsigned char>(c);
        if (std::isalnum(byte) || std::strchr("-._~/", c)) {
            out += c;
        } else {
            out += '%';
            out += hex[byte >> 4];
            out += hex[byte & 15];
        }
    }
    return out;
}

std::string token(std::string_view text) {
    std::string out;
    for (char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (std::isalnum(byte) && byte < 128) out += char(std::tolower(byte));
        else if (c == '_' || c == '-') out += c;
        else out += '-';
    }
    return out.empty() ? "unnamed" : out;
}

std::string text(const json& object, const char* key) {
    if (!object.is_object()) return {};
    auto it = object.find(key);
    if (it == object.end()) return {};
    if (it->is_string()) return it->get<std::string>();
    if (it->is_number() || it->is_boolean()) return it->dump();
    return {};
}

std::optional<double> number(const json& object, const char* key) {
    if (!object.is_object()) return std::nullopt;
    auto it = object.find(key);
    if (it == object.end() || !it->is_number()) return std::nullopt;
    return it->get<double>();
}

const json& array(const json& object, const char* key) {
    static const json empty = json::array();
    if (!object.is_object()) return empty;
    auto it = object.find(key);
    return it != object.end() && it->is_array() ? *it : empty;
}

const json& object(const json& parent, const char* key) {
    static const json empty = json::object();
    if (!parent.is_object()) return empty;
    auto it = parent.find(key);
    return it != parent.end() && it->is_object() ? *it : empty;
}

std::string formatNumber(double value, int decimals) {
    if (std::isnan(value)) return "NaN";
    if (std::isinf(value)) return value > 0 ? "\u221e" : "-\u221e";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    std::string out = buffer;
    if (out.find('.') != std::string::npos) {
        while (out.back() == '0') out.pop_back();
        if (out.back() == '.') out.pop_back();
    }
    return out == "-0" ? "0" : out;
}

std::string formatScore(std::optional<double> score, std::optional<double> maxScore) {
    // Nothing to earn (a worked example): no "0 / 0".
    if (maxScore && *maxScore == 0.0) return score && *score != 0.0 ? formatNumber(*score, 2) : "not graded";
    const std::string value = score ? formatNumber(*score, 2) : "\u2013";
    return maxScore ? value + " / " + formatNumber(*maxScore, 2) : value;
}

std::string formatSeconds(double seconds) {
    if (seconds < 60.0) return formatNumber(seconds, 1) + " s";
    const long total = std::lround(seconds);
    return std::to_string(total / 60) + " min " + std::to_string(total % 60) + " s";
}

namespace {

// [6, 7, 5] -> "6 x 7 x 5"; anything else as JSON.
std::string triple(const json& values) {
    if (!values.is_array()) return values.dump();
    std::string out;
    for (const json& v : values)
        out += (out.empty() ? "" : " x ") + (v.is_number() ? formatNumber(v.get<double>(), 6) : v.dump());
    return out;
}

}  // namespace

std::string checkInputsText(const json& inputs) {
    std::string out;
    const std::string seed = text(inputs, "seed");
    if (!seed.empty()) out += "seed " + seed;
    const json& volume = object(inputs, "volume");
    if (!volume.empty()) {
        out += std::string(out.empty() ? "" : "; ") + "random volume of " + triple(volume.value("dims", json())) +
               " voxels, spacing " + triple(volume.value("spacing", json())) + " (box " +
               triple(volume.value("extent", json())) + ")";
        const std::string values = text(volume, "values");
        if (!values.empty()) out += "; " + values;
    }
    const std::string units = text(inputs, "units");
    if (!units.empty()) out += std::string(out.empty() ? "" : "; ") + "units: " + units;
    return out;
}

std::string statusLabel(const std::string& status) {
    std::string label = status;
    std::replace(label.begin(), label.end(), '_', ' ');
    return label;
}

std::string badge(const std::string& status) {
    const std::string shown = status.empty() ? "unknown" : status;
    return "<span class=\"badge st-" + token(shown) + "\">" + escape(statusLabel(shown)) + "</span>";
}

std::string scoreBar(std::optional<double> score, std::optional<double> maxScore) {
    if (!score || !maxScore || !(*maxScore > 0.0)) return {};
    const double fraction = std::clamp(*score / *maxScore, 0.0, 1.0);
    // Full marks green, partial credit amber, nothing red.
    const char* level = fraction >= 0.9995 ? "full" : fraction > 0.0 ? "partial" : "none";
    return "<span class=\"bar\"><span class=\"fill " + std::string(level) + "\" style=\"width:" +
           formatNumber(fraction * 100.0, 1) + "%\"></span></span>";
}

std::string page(const std::string& title, const std::string& body, const std::string& script) {
    std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
                      "<title>" + escape(title) + "</title>\n<style>\n" + reportStyleSheet + "</style>\n</head>\n" +
                      "<body>\n" + body;
    if (!script.empty()) out += "<script>\n" + script + "</script>\n";
    return out + "</body>\n</html>\n";
}

}  // namespace voxlab::html
