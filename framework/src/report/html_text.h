// voxlab: small pieces shared by the grader's HTML reports — escaping text
// from results, reading optional JSON fields without throwing, formatting
// numbers and scores, and the page around a body.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace voxlab::html {

// Text made safe for HTML element content and quoted attribute values:
// & < > " ' become character references, and invalid UTF-8 becomes U+FFFD
// (safeText in untrusted_text.h).
std::string escape(std::string_view text);

// A relative path made safe for an href or src attribute: every byte outside
// [A-Za-z0-9-._~/] is percent-encoded (so it also needs no HTML escaping).
std::string urlPath(std::string_view path);

// A token for a CSS class or an element id: [a-z0-9_-] kept (letters
// lowered), anything else becomes '-'. Never empty.
std::string token(std::string_view text);

// Optional fields of a results object. Wrong types count as missing.
std::string text(const nlohmann::json& object, const char* key);
std::optional<double> number(const nlohmann::json& object, const char* key);
const nlohmann::json& array(const nlohmann::json& object, const char* key);
const nlohmann::json& object(const nlohmann::json& parent, const char* key);

// value with at most `decimals` decimals, trailing zeros dropped: 8.2, 10, 0.031.
std::string formatNumber(double value, int decimals);
// "8.2 / 10", "8.2", "– / 10" or "–"; "not graded" out of 0 points (a worked example).
std::string formatScore(std::optional<double> score, std::optional<double> maxScore);
// "41.2 s", "3 min 5 s".
std::string formatSeconds(double seconds);

// A function check's "inputs" (function_checks.h: CheckComparison::inputs) in
// one line of plain text: "seed 0x5EED000A; random volume 6 x 7 x 5 voxels,
// spacing 1.3 x 0.8 x 1.1 (box ...); data value = ...; units: ...". Empty
// when there is nothing to say.
std::string checkInputsText(const nlohmann::json& inputs);

// "not_implemented" -> "not implemented".
std::string statusLabel(const std::string& status);
// <span class="badge st-STATUS">label</span>
std::string badge(const std::string& status);
// A horizontal bar filled to score / max (nothing when either is missing).
std::string scoreBar(std::optional<double> score, std::optional<double> maxScore);

// A whole page: doctype, head with the inline style sheet, then `body`.
// `script` (may be empty) goes into an inline <script> at the end.
std::string page(const std::string& title, const std::string& body, const std::string& script);

// The reports' inline style sheet and the class table's sorting script
// (html_report_style.cpp).
extern const char* const reportStyleSheet;
extern const char* const sortableTableScript;
// Moves the split of each comparison (.compare .slider) as its slider moves.
extern const char* const compareSliderScript;

}  // namespace voxlab::html
