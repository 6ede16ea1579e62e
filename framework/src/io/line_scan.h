// voxlab: a cursor over one line of text, for the small hand-written
// parsers that read students' files and compiler logs (shader.cpp's
// #include and #version lines and log formats, stub_scan.cpp's stubs and
// signatures). Every step moves forward, so a parse is linear in the line's
// length: no regular-expression engine, whose backtracking recurses per
// character and overflows the stack on a long line, runs on a submission.
//
// Character classes are std::regex's in the "C" locale: a space is one of
// " \t\n\v\f\r", a word character is an ASCII letter, digit or '_'.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace voxlab::scan {

inline bool isSpace(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }
inline bool isDigit(char c) { return c >= '0' && c <= '9'; }
inline bool isWord(char c) {
    return isDigit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

struct Line {
    std::string_view text;
    std::size_t at = 0;

    bool done() const { return at >= text.size(); }
    // Skips spaces; true when there was at least one.
    bool spaces() {
        const std::size_t from = at;
        while (at < text.size() && isSpace(text[at])) ++at;
        return at > from;
    }
    // Takes `word` when the text goes on with it.
    bool literal(std::string_view word) {
        if (text.substr(at, word.size()) != word) return false;
        at += word.size();
        return true;
    }
    // Takes one or more word characters.
    bool identifier(std::string* out) {
        const std::size_t from = at;
        while (at < text.size() && isWord(text[at])) ++at;
        if (out) *out = std::string(text.substr(from, at - from));
        return at > from;
    }
    // Takes one or more digits; false for none, or for more than 18 (no
    // line or column number is that long, and it would not fit a long).
    bool number(long* out) {
        const std::size_t from = at;
        long value = 0;
        for (; at < text.size() && isDigit(text[at]); ++at)
            if (at - from < 18) value = value * 10 + (text[at] - '0');
        if (at == from || at - from > 18) return false;
        if (out) *out = value;
        return true;
    }
    // Takes the rest of the line when it holds neither CR nor LF (std::regex's `.*$`).
    bool restOfLine(std::string* out) {
        const std::string_view rest = text.substr(at);
        if (rest.find_first_of("\r\n") != std::string_view::npos) return false;
        if (out) *out = std::string(rest);
        at = text.size();
        return true;
    }
    // What may end a directive: spaces, then nothing or a // comment
    // (std::regex's `\s*(//.*)?$`; with `finalCr`, `\s*(//.*)?\r?$`).
    bool commentOrEnd(bool finalCr = false) {
        spaces();
        if (done()) return true;
        if (!literal("//")) return false;
        std::string_view rest = text.substr(at);
        if (finalCr && !rest.empty() && rest.back() == '\r') rest.remove_suffix(1);
        return rest.find_first_of("\r\n") == std::string_view::npos;
    }
};

}  // namespace voxlab::scan
