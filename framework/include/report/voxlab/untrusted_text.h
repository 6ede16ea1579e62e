// voxlab: text that comes from a submission, made safe to keep and to show.
//
// Everything a student controls that the grader turns into text (file and
// folder names, compiler output, what a worker printed or sent, exception
// messages, check values) is data, never markup, terminal commands or
// spreadsheet formulas. It passes through safeText() where it enters the
// grader's data (RunOutcome, WorkerResults, the report's JSON), and through
// the functions below where it leaves: the terminal, a CSV cell, a folder
// name. JSON reports are written with reportJsonText(), which replaces any
// invalid UTF-8 that got past the boundary instead of throwing.
//
// Pure functions of their input: no files, no GL (the fuzz target
// tests/fuzz/fuzz_report_text.cpp links them alone).
#pragma once

#include <cstddef>
#include <set>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace voxlab {

// Caps on text from a submission: a name (a file, a folder, a student), a
// one-line message, and a log (a compiler's or a worker's output).
inline constexpr std::size_t kMaxNameBytes = 256;
inline constexpr std::size_t kMaxMessageBytes = 4096;
inline constexpr std::size_t kMaxLogBytes = std::size_t(1) << 20;

// True when `bytes` is well-formed UTF-8 (no overlong forms, surrogates or
// code points past U+10FFFF).
bool isValidUtf8(std::string_view bytes);

// `bytes` as valid UTF-8: each byte that does not belong to a well-formed
// sequence becomes U+FFFD. Longer than `maxBytes`, it is cut at a character
// boundary and ends with a marker saying how many bytes were cut
// (" [... 1234 bytes cut]").
std::string safeText(std::string_view bytes, std::size_t maxBytes = kMaxMessageBytes);

// safeText() without control characters, for a terminal: C0 controls other
// than newline and tab, DEL, C1 controls (U+0080 to U+009F) and whole escape
// sequences (ESC [ ... final byte, ESC ] ... BEL or ESC \, ESC and one
// character) are removed.
std::string terminalText(std::string_view bytes, std::size_t maxBytes = kMaxMessageBytes);

// terminalText() on one line: newlines, tabs and carriage returns become spaces.
std::string terminalLine(std::string_view bytes, std::size_t maxBytes = kMaxMessageBytes);

// One CSV cell (RFC 4180), safe to open in a spreadsheet: terminalText()
// (valid UTF-8, no control characters but newline and tab); a cell that
// begins with = + - @ tab or carriage return gets a leading single
// quote (OWASP's rule against CSV injection) and is quoted; a cell holding a
// comma, a quote, a newline or a carriage return is quoted, quotes doubled.
std::string csvCell(std::string_view text);

// A folder name for a student's report (OUT/<folder>/): ASCII letters,
// digits, '-', '_' and '.', not starting with a dot, at most 100 bytes; every
// other byte (or run of them) becomes '_'. A name the grader writes into
// OUT itself (gradebook.csv, index.html, similarity.html, similarity.json,
// ...) or one already in `taken` (compared without case) gets a suffix -2,
// -3, ...; the result is added to `taken`. An ordinary name comes back as it
// is.
std::string safeFolderName(std::string_view name, std::set<std::string>& taken);

// A report's JSON text (indented by 2, with a final newline); invalid UTF-8
// anywhere in it is replaced by U+FFFD instead of throwing.
std::string reportJsonText(const nlohmann::json& report);

}  // namespace voxlab
