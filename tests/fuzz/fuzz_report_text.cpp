// libFuzzer target: students' text through the grader's report writers
// (voxlab/untrusted_text.h, html_report.h, grader.h).
//
// The input is up to six texts a submission controls, split at each NUL
// byte: a student's name, a file name, a compiler log, a stage's message,
// a check's example and a layout note. They fill every text field of a
// graded report (report.json's schema in html_report.h), which then goes
// through each writer:
//   - report.json (reportJsonText): valid UTF-8 that parses back;
//   - Gradescope's results.json (gradescopeResults): the same;
//   - the submission's and the class's HTML pages (htmlReportPage,
//     classHtmlReportPage, which writeHtmlReport and writeClassHtmlReport
//     save): valid UTF-8, and no '<' of the input's reaches
//     the page raw: the pages hold exactly as many '<' when every '<' of
//     the input is replaced by DEL (0x7F);
//   - the gradebook (gradebookCsv): valid UTF-8, and no cell, parsed as
//     RFC 4180, starts a formula (= + - @ tab CR);
//   - the terminal summary (summaryTable) and terminalText: valid UTF-8 and
//     no control byte but newline (and tab for terminalText), no DEL, no C1.
// Besides the error contract (fuzz_common.h): any exception is a finding,
// as the writers never throw for what a submission holds.
#include <algorithm>
#include <cstring>
#include <vector>

#include <nlohmann/json.hpp>

#include "fuzz_common.h"
#include "voxlab/grader.h"
#include "voxlab/html_report.h"
#include "voxlab/untrusted_text.h"

namespace {

using nlohmann::json;
using voxlab::fuzz::require;

std::vector<std::string> splitFields(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> fields(1);
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == 0 && fields.size() < 6) fields.emplace_back();
        else fields.back() += char(data[i]);
    }
    fields.resize(6);
    return fields;
}

// A graded report whose text fields are the input's.
json reportOf(const std::vector<std::string>& f) {
    // (No "images": the grader names them from the manifest, and a page reads their sizes from disk.)
    const json scene = {{"name", f[1]}, {"status", "error"}, {"message", f[3]}, {"score", 0.5}, {"max_score", 1.0},
                        {"scene_file", f[1]}, {"setup", f[3]}};
    const json check = {{"name", f[1]}, {"status", "failed"}, {"message", f[3]}, {"examples", {f[4], json{{"got", f[3]}}}},
                        {"score", 0.0}, {"max_score", 1.0}};
    const json stage = {{"stage", f[1]}, {"title", f[0]}, {"status", "compile_error"}, {"message", f[3]},
                        {"log", f[2]}, {"score", 1.5}, {"max_score", 10.0}, {"not_implemented", {f[1]}},
                        {"hints", {f[4]}}, {"scenes", {scene}}, {"checks", {check}}};
    json other = stage;
    other["status"] = "failed";
    return {{"name", f[0]}, {"submission", f[1]}, {"layout_note", f[5]}, {"status", "error"}, {"message", f[3]},
            {"mode", "grade"}, {"score", 1.5}, {"max_score", 20.0}, {"stages", {stage, other}}};
}

bool terminalSafe(const std::string& text, bool tabs) {
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if ((c < 0x20 && c != '\n' && !(tabs && c == '\t')) || c == 0x7F) return false;
        if (c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) <= 0x9F) return false;
    }
    return true;
}

// The cells of a CSV text (RFC 4180: quoted cells may hold separators).
std::vector<std::string> csvCells(const std::string& csv) {
    std::vector<std::string> cells(1);
    bool quoted = false;
    for (std::size_t i = 0; i < csv.size(); ++i) {
        const char c = csv[i];
        if (quoted && c == '"' && i + 1 < csv.size() && csv[i + 1] == '"') cells.back() += c, ++i;
        else if (c == '"') quoted = !quoted;
        else if (!quoted && (c == ',' || c == '\n')) cells.emplace_back();
        else cells.back() += c;
    }
    return cells;
}

// The two HTML pages of `report`: the submission's (its images' folder is
// one that does not exist) and the class's.
std::string pagesOf(const json& report) {
    return voxlab::htmlReportPage(report, voxlab::fuzz::scratchDir() + "/none") +
           voxlab::classHtmlReportPage(json{{"submissions", {report}}});
}

void checkWriters(const std::vector<std::string>& fields) {
    const json report = reportOf(fields);
    const std::string text = voxlab::reportJsonText(report);
    require(voxlab::isValidUtf8(text), "report.json is not valid UTF-8");
    require(!json::parse(text, nullptr, false).is_discarded(), "report.json does not parse back");
    const std::string results = voxlab::reportJsonText(voxlab::gradescopeResults(report));
    require(voxlab::isValidUtf8(results) && !json::parse(results, nullptr, false).is_discarded(),
            "results.json is not valid UTF-8 JSON");

    const std::string pages = pagesOf(report);
    require(voxlab::isValidUtf8(pages), "an HTML page is not valid UTF-8");
    std::vector<std::string> tame = fields;
    for (std::string& f : tame) std::replace(f.begin(), f.end(), '<', '\x7f');
    require(std::count(pages.begin(), pages.end(), '<') == [&] {
        const std::string other = pagesOf(reportOf(tame));
        return std::count(other.begin(), other.end(), '<');
    }(), "a '<' of the input reached an HTML page unescaped");

    const std::string csv = voxlab::gradebookCsv({report});
    require(voxlab::isValidUtf8(csv), "the gradebook is not valid UTF-8");
    for (const std::string& cell : csvCells(csv))
        require(cell.empty() || !std::strchr("=+-@\t\r", cell[0]), "a gradebook cell starts a formula", cell);

    const std::string table = voxlab::summaryTable(report);
    require(voxlab::isValidUtf8(table) && terminalSafe(table, false), "the summary table holds a control byte");
    for (const std::string& f : fields) {
        const std::string shown = voxlab::terminalText(f);
        require(voxlab::isValidUtf8(shown) && terminalSafe(shown, true), "terminalText let a control byte through", f);
        const std::string line = voxlab::terminalLine(f);
        require(terminalSafe(line, false), "terminalLine let a control byte through", f);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::string> fields = splitFields(data, size);
    voxlab::fuzz::expectOnlyVoxlabErrors([&] { checkWriters(fields); });
    return 0;
}
