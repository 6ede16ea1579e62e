// voxlab: text from a submission made safe to keep and to show (see
// untrusted_text.h). Every function is one pass over its input.
#include "voxlab/untrusted_text.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include <nlohmann/json.hpp>

namespace voxlab {

namespace {

constexpr const char* kReplacement = "\xEF\xBF\xBD";  // U+FFFD
constexpr unsigned char kEsc = 0x1B;

bool continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

// The bytes allowed second in a sequence that starts with `lead` (the
// ranges that exclude overlong forms, surrogates and code points past
// U+10FFFF), and the sequence's length; 0 for a byte that starts none.
std::size_t sequenceLength(unsigned char lead, unsigned char* low, unsigned char* high) {
    *low = 0x80, *high = 0xBF;
    if (lead < 0x80) return 1;
    if (lead >= 0xC2 && lead <= 0xDF) return 2;
    if (lead == 0xE0) *low = 0xA0;
    if (lead == 0xED) *high = 0x9F;
    if (lead >= 0xE0 && lead <= 0xEF) return 3;
    if (lead == 0xF0) *low = 0x90;
    if (lead == 0xF4) *high = 0x8F;
    if (lead >= 0xF0 && lead <= 0xF4) return 4;
    return 0;
}

// How many bytes at `at` form one character (*valid) or, when they do not,
// the longest start of one (at least 1 byte), which becomes one U+FFFD.
std::size_t nextCharacter(std::string_view s, std::size_t at, bool* valid) {
    unsigned char low, high;
    const std::size_t n = sequenceLength(static_cast<unsigned char>(s[at]), &low, &high);
    *valid = false;
    if (n == 0) return 1;
    std::size_t k = 1;
    for (; k < n && at + k < s.size(); ++k) {
        const auto c = static_cast<unsigned char>(s[at + k]);
        if (k == 1 ? (c < low || c > high) : !continuation(c)) break;
    }
    *valid = k == n;
    return k;
}

// Skips the escape sequence that starts with ESC at `at`; returns where the
// text goes on.
std::size_t skipEscape(std::string_view s, std::size_t at) {
    std::size_t i = at + 1;
    if (i >= s.size()) return i;
    const auto kind = static_cast<unsigned char>(s[i]);
    const auto byteAt = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    if (kind == '[') {  // CSI: parameters, intermediates, one final byte
        ++i;
        while (i < s.size() && byteAt(i) >= 0x30 && byteAt(i) <= 0x3F) ++i;
        while (i < s.size() && byteAt(i) >= 0x20 && byteAt(i) <= 0x2F) ++i;
        return i < s.size() && byteAt(i) >= 0x40 && byteAt(i) <= 0x7E ? i + 1 : i;
    }
    if (std::strchr("]PX^_", kind)) {  // OSC, DCS, SOS, PM, APC: a string up to BEL or ESC '\'
        for (++i; i < s.size(); ++i) {
            if (byteAt(i) == 0x07) return i + 1;
            if (byteAt(i) == kEsc) return i + 1 < s.size() && s[i + 1] == '\\' ? i + 2 : i + 1;
        }
        return i;
    }
    while (i < s.size() && byteAt(i) >= 0x20 && byteAt(i) <= 0x2F) ++i;  // intermediates, then the final byte
    return i < s.size() && byteAt(i) >= 0x30 && byteAt(i) <= 0x7E ? i + 1 : i;
}

std::string lowered(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool reservedInOut(const std::string& lowerName) {
    static const char* const names[] = {"gradebook.csv", "index.html",  "similarity.html",
                                        "similarity.json", "report.json", "results.json"};
    return std::any_of(std::begin(names), std::end(names), [&](const char* n) { return lowerName == n; });
}

}  // namespace

bool isValidUtf8(std::string_view bytes) {
    for (std::size_t i = 0; i < bytes.size();) {
        bool valid = false;
        i += nextCharacter(bytes, i, &valid);
        if (!valid) return false;
    }
    return true;
}

std::string safeText(std::string_view bytes, std::size_t maxBytes) {
    std::string out;
    out.reserve(std::min(bytes.size(), maxBytes) + 32);
    std::size_t i = 0;
    while (i < bytes.size()) {
        bool valid = false;
        const std::size_t n = nextCharacter(bytes, i, &valid);
        const std::size_t size = valid ? n : 3;
        if (out.size() + size > maxBytes) break;
        if (valid) out.append(bytes.data() + i, n);
        else out += kReplacement;
        i += n;
    }
    if (i < bytes.size()) out += " [... " + std::to_string(bytes.size() - i) + " bytes cut]";
    return out;
}

std::string terminalText(std::string_view bytes, std::size_t maxBytes) {
    const std::string text = safeText(bytes, maxBytes);
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c == kEsc) {
            i = skipEscape(text, i);
        } else if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7F) {
            ++i;
        } else if (c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) <= 0x9F) {
            i += 2;  // a C1 control, U+0080 to U+009F
        } else {
            out += text[i++];
        }
    }
    return out;
}

std::string terminalLine(std::string_view bytes, std::size_t maxBytes) {
    std::string out = terminalText(bytes, maxBytes);
    std::replace(out.begin(), out.end(), '\n', ' ');
    std::replace(out.begin(), out.end(), '\t', ' ');
    return out;
}

std::string csvCell(std::string_view text) {
    constexpr std::size_t kMaxCellBytes = 32000;  // spreadsheets hold 32767 characters a cell
    std::string cell = terminalText(text, kMaxCellBytes);  // no escape sequence hides what the cell begins with
    const bool formula = !cell.empty() && std::strchr("=+-@\t\r", cell[0]) != nullptr;
    if (formula) cell.insert(0, 1, '\'');
    if (!formula && cell.find_first_of(",\"\n\r") == std::string::npos) return cell;
    std::string quoted = "\"";
    for (char c : cell) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string safeFolderName(std::string_view name, std::set<std::string>& taken) {
    constexpr std::size_t kMaxFolderBytes = 100;
    std::string base;
    bool replaced = false;
    for (const char c : name) {
        const auto byte = static_cast<unsigned char>(c);
        const bool keep = byte < 0x80 && (std::isalnum(byte) || c == '-' || c == '_' || c == '.');
        if (keep) base += c;
        else if (!replaced) base += '_';
        replaced = !keep;
    }
    if (base.size() > kMaxFolderBytes) base.resize(kMaxFolderBytes);
    if (base.empty()) base = "_";
    if (base[0] == '.') base[0] = '_';
    std::string folder = base;
    for (int n = 2; reservedInOut(lowered(folder)) || taken.count(lowered(folder)); ++n)
        folder = base + "-" + std::to_string(n);
    taken.insert(lowered(folder));
    return folder;
}

std::string reportJsonText(const nlohmann::json& report) {
    return report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace voxlab
