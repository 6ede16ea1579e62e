// voxlab: a class's gradebook as one sortable HTML table (schema in
// html_report.h): a row per submission, a column per stage, each row linking
// to the submission's own report folder.
#include <filesystem>
#include <map>
#include <vector>

#include "html_text.h"
#include "voxlab/atomic_file.h"
#include "voxlab/html_report.h"

namespace voxlab {
namespace {

using nlohmann::json;

struct StageColumn {
    std::string stage, title;
    std::optional<double> maxScore;
    double sum = 0.0;
    int count = 0;
};

// The stages in the order they first appear, so that a submission missing
// a stage still lines up with the others.
std::vector<StageColumn> stageColumns(const json& submissions) {
    std::vector<StageColumn> columns;
    std::map<std::string, std::size_t> index;
    for (const json& submission : submissions) {
        for (const json& stage : html::array(submission, "stages")) {
            const std::string name = html::text(stage, "stage");
            if (index.count(name)) continue;
            index[name] = columns.size();
            columns.push_back({name, html::text(stage, "title"), html::number(stage, "max_score")});
        }
    }
    return columns;
}

const json* findStage(const json& submission, const std::string& name) {
    for (const json& stage : html::array(submission, "stages"))
        if (html::text(stage, "stage") == name) return &stage;
    return nullptr;
}

// A numeric sort key; a missing value sorts below every score.
std::string sortKey(std::optional<double> value) { return value ? html::formatNumber(*value, 6) : "-1"; }

std::optional<double> total(const json& submission, const char* key, const char* stageKey) {
    if (auto value = html::number(submission, key)) return value;
    const json& stages = html::array(submission, "stages");
    if (stages.empty()) return std::nullopt;
    double sum = 0.0;
    for (const json& stage : stages) sum += html::number(stage, stageKey).value_or(0.0);
    return sum;
}

// The class's totals, for the mean; the maximum is shown only when every submission shares it.
struct Totals {
    double sum = 0.0;
    int count = 0;
    std::optional<double> maxScore;
    bool first = true, sameMax = true;

    void add(std::optional<double> score, std::optional<double> max) {
        if (score) sum += *score, ++count;
        if (first) maxScore = max, first = false;
        else if (max != maxScore) sameMax = false;
    }
};

std::string row(const json& submission, std::vector<StageColumn>& columns, Totals& totals) {
    const std::string name = html::text(submission, "name");
    std::string link = html::text(submission, "report");
    if (link.empty()) link = name + "/index.html";
    const auto score = total(submission, "score", "score"), maxScore = total(submission, "max_score", "max_score");
    totals.add(score, maxScore);

    std::string out = "<tr><td data-sort=\"" + html::escape(name) + "\"><a href=\"" + html::urlPath(link) + "\">" +
                      html::escape(name.empty() ? std::string("(unnamed)") : name) + "</a></td>";
    out += "<td class=\"num total-cell\" data-sort=\"" + sortKey(score) + "\">" +
           html::escape(html::formatScore(score, maxScore)) + html::scoreBar(score, maxScore) + "</td>";

    int passed = 0, graded = 0;
    for (StageColumn& column : columns) {
        const json* stage = findStage(submission, column.stage);
        if (!stage) {
            out += "<td class=\"num cell\" data-sort=\"-1\">\u2013</td>";
            continue;
        }
        const std::string status = html::text(*stage, "status");
        const auto stageScore = html::number(*stage, "score");
        if (stageScore) column.sum += *stageScore, ++column.count;
        ++graded;
        if (status == "passed") ++passed;
        std::string tip = html::statusLabel(status);
        const std::string message = html::text(*stage, "message");
        if (!message.empty()) tip += ": " + message;
        out += "<td class=\"num cell cell-" + html::token(status.empty() ? "unknown" : status) + "\" data-sort=\"" +
               sortKey(stageScore) + "\" title=\"" + html::escape(tip) + "\">" +
               (stageScore ? html::formatNumber(*stageScore, 2) : std::string("\u2013")) + "</td>";
    }

    // The submission's own status when it has one (e.g. it did not build), else how many stages passed.
    const std::string status = html::text(submission, "status");
    const std::string message = html::text(submission, "message");
    if (!status.empty()) {
        out += "<td data-sort=\"" + html::escape(status) + "\">" + html::badge(status);
        if (!message.empty()) out += " <span class=\"sub\">" + html::escape(message) + "</span>";
    } else {
        out += "<td data-sort=\"" + std::to_string(passed) + "\">" + std::to_string(passed) + " of " +
               std::to_string(graded) + " stages passed";
    }
    return out + "</td></tr>\n";
}

}  // namespace

void writeClassHtmlReport(const json& gradebook, const std::string& dir) {
    const json& submissions = gradebook.is_array() ? gradebook : html::array(gradebook, "submissions");
    std::vector<StageColumn> columns = stageColumns(submissions);
    std::string title = html::text(gradebook, "title");
    if (title.empty()) title = "Class gradebook";

    std::string rows;
    Totals totals;
    for (const json& submission : submissions) rows += row(submission, columns, totals);

    std::string body = "<header class=\"top\"><div class=\"who\"><div class=\"kicker\">voxlab grade</div><h1>" +
                       html::escape(title) + "</h1><dl class=\"meta\">";
    const std::string gradedAt = html::text(gradebook, "graded_at");
    if (!gradedAt.empty()) body += "<div><dt>Graded</dt><dd>" + html::escape(gradedAt) + "</dd></div>";
    body += "<div><dt>Submissions</dt><dd>" + std::to_string(submissions.size()) + "</dd></div>";
    if (auto seconds = html::number(gradebook, "elapsed_s"))
        body += "<div><dt>Time</dt><dd>" + html::formatSeconds(*seconds) + "</dd></div>";
    body += "</dl></div>";
    if (totals.count > 0) {
        body += "<div class=\"total\"><div class=\"total-score\">" + html::formatNumber(totals.sum / totals.count, 1);
        if (totals.sameMax && totals.maxScore)
            body += "<span class=\"of\"> / " + html::formatNumber(*totals.maxScore, 2) + "</span>";
        body += "</div><div class=\"percent\">mean score</div></div>";
    }
    body += "</header>\n<main><section class=\"card wide-table\"><table class=\"gradebook sortable\"><thead><tr>"
            "<th>Submission</th><th class=\"num\">Total</th>";
    for (const StageColumn& column : columns) {
        const std::string tip = column.title.empty() ? column.stage : column.title;
        body += "<th class=\"num\" title=\"" + html::escape(tip) + "\">" + html::escape(column.stage);
        if (column.maxScore) body += "<div class=\"sub\">/ " + html::formatNumber(*column.maxScore, 2) + "</div>";
        body += "</th>";
    }
    body += "<th>Status</th></tr></thead><tbody>\n" + rows + "</tbody>";
    if (totals.count > 0) {
        body += "<tfoot><tr><td>Mean</td><td class=\"num\">" + html::formatNumber(totals.sum / totals.count, 2) +
                "</td>";
        for (const StageColumn& column : columns)
            body += "<td class=\"num\">" +
                    (column.count ? html::formatNumber(column.sum / column.count, 2) : "\u2013") + "</td>";
        body += "<td></td></tr></tfoot>";
    }
    body += "</table><p class=\"legend\">Click a column heading to sort by it; hover over a score for the stage's "
            "status and message.</p></section></main>\n<footer>Written by voxlab grade. Each name links to that "
            "submission's report.</footer>\n";

    writeFileAtomically((std::filesystem::path(dir) / "index.html").string(),
                        html::page(title, body, html::sortableTableScript));
}

}  // namespace voxlab
