// voxlab: a class's gradebook as one sortable HTML table (schema in
// html_report.h): a row per submission, a column per stage, each row linking
// to the submission's own report folder.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <vector>

#include "html_text.h"
#include "voxlab/atomic_file.h"
#include "voxlab/html_report.h"
#include "voxlab/untrusted_text.h"

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
// a stage still lines up with the others. A stage worth 0 points in every
// submission (a worked example) gets no column: there is nothing to show
// but "0 / 0" (a problem with it still shows in the submission's cell).
std::vector<StageColumn> stageColumns(const json& submissions) {
    std::vector<StageColumn> columns;
    std::map<std::string, std::size_t> index;
    for (const json& submission : submissions) {
        for (const json& stage : html::array(submission, "stages")) {
            const std::string name = html::text(stage, "stage");
            const auto maxScore = html::number(stage, "max_score");
            if (index.count(name)) {
                StageColumn& column = columns[index[name]];
                if (maxScore && (!column.maxScore || *maxScore > *column.maxScore)) column.maxScore = maxScore;
                continue;
            }
            index[name] = columns.size();
            columns.push_back({name, html::text(stage, "title"), maxScore});
        }
    }
    columns.erase(std::remove_if(columns.begin(), columns.end(),
                                 [](const StageColumn& c) { return c.maxScore && *c.maxScore == 0.0; }),
                  columns.end());
    return columns;
}

// A name escaped, with a line-break opportunity after each underscore.
std::string breakable(const std::string& name) {
    std::string out;
    for (char c : html::escape(name)) out += c == '_' ? std::string("_<wbr>") : std::string(1, c);
    return out;
}

// How bad a stage's status is, for ordering problems: what stopped the
// stage from running at all comes first, then wrong results, then work not
// handed in.
int severity(const std::string& status) {
    if (status == "compile_error") return 0;
    if (status == "crashed") return 1;
    if (status == "timeout") return 2;
    if (status == "failed") return 4;
    if (status == "not_implemented") return 5;
    if (status == "blocked") return 6;  // a prerequisite's stub kept scenes from running (a self-check)
    return 3;  // error, and any status not named here
}

// The short text a stage's cell shows under its score: none for passed and
// failed (the score and its colour say it).
std::string cellNote(const std::string& status) {
    if (status.empty() || status == "passed" || status == "failed" || status == "example") return "";
    if (status == "not_implemented") return "not impl.";
    return html::statusLabel(status);
}

// What went wrong with a submission, worst first, as visible text: each
// error on its own line with its message, failed and unfinished stages
// grouped.
std::string problemsBlock(const json& submission) {
    std::string out;
    std::map<std::string, std::string> grouped;  // failed, not_implemented -> "mip, iso"
    for (const StageProblem& p : stageProblems(submission)) {
        if (severity(p.status) > 3) {
            std::string& names = grouped[p.status];
            names += (names.empty() ? "" : ", ") + p.stage;
            continue;
        }
        out += "<div class=\"prob p-" + html::token(p.status) + "\"><b>" + html::escape(html::statusLabel(p.status)) +
               "</b> in " + html::escape(p.stage);
        if (!p.message.empty()) out += ": <span class=\"why\">" + html::escape(p.message) + "</span>";
        out += "</div>";
    }
    for (const char* status : {"failed", "not_implemented", "blocked"})
        if (grouped.count(status))
            out += "<div class=\"prob p-" + html::token(status) + "\"><b>" + html::statusLabel(status) + "</b>: " +
                   html::escape(grouped[status]) + "</div>";
    return out.empty() ? "" : "<div class=\"probs\">" + out + "</div>";
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

    // The name's cell also says what went wrong: the submission's own status
    // (e.g. it did not build), then its stages' problems, worst first.
    std::string out = "<tr><td class=\"who\" data-sort=\"" + html::escape(name) + "\"><a href=\"" +
                      html::urlPath(link) + "\">" + breakable(name.empty() ? std::string("(unnamed)") : name) + "</a>";
    const std::string status = html::text(submission, "status"), message = html::text(submission, "message");
    if (!status.empty())
        out += "<div class=\"prob\">" + html::badge(status) + (message.empty() ? "" : " " + html::escape(message)) +
               "</div>";
    // Not graded at all: the reason above says it once, not again for every stage.
    out += (status == "error" ? std::string() : problemsBlock(submission)) + "</td>";
    out += "<td class=\"num total-cell\" data-sort=\"" + sortKey(score) + "\">" +
           html::escape(html::formatScore(score, maxScore)) + html::scoreBar(score, maxScore) + "</td>";

    for (StageColumn& column : columns) {
        const json* stage = findStage(submission, column.stage);
        if (!stage) {
            out += "<td class=\"num cell\" data-sort=\"-1\">\u2013</td>";
            continue;
        }
        const std::string stageStatus = html::text(*stage, "status");
        const auto stageScore = html::number(*stage, "score");
        if (stageScore) column.sum += *stageScore, ++column.count;
        std::string tip = html::statusLabel(stageStatus);
        const std::string stageMessage = html::text(*stage, "message");
        if (!stageMessage.empty()) tip += ": " + stageMessage;
        // Nothing handed in (not implemented, no points): a dash, as for a stage missing altogether.
        const bool nothing = stageStatus == "not_implemented" && stageScore.value_or(0.0) == 0.0;
        const std::string note = nothing ? "" : cellNote(stageStatus);
        out += "<td class=\"num cell cell-" + html::token(stageStatus.empty() ? "unknown" : stageStatus) +
               "\" data-sort=\"" + sortKey(stageScore) + "\" title=\"" + html::escape(tip) + "\">" +
               (stageScore && !nothing ? html::formatNumber(*stageScore, 2) : std::string("\u2013")) +
               (note.empty() ? "" : "<div class=\"note\">" + html::escape(note) + "</div>") + "</td>";
    }
    return out + "</tr>\n";
}

}  // namespace

std::vector<StageProblem> stageProblems(const json& results) {
    std::vector<StageProblem> out;
    for (const json& stage : html::array(results, "stages")) {
        const std::string status = html::text(stage, "status");
        if (status == "passed" || status == "example") continue;
        out.push_back({html::text(stage, "stage"), status.empty() ? "unknown" : status, html::text(stage, "message")});
    }
    std::stable_sort(out.begin(), out.end(), [](const StageProblem& a, const StageProblem& b) {
        return severity(a.status) < severity(b.status);
    });
    return out;
}

std::string problemsSummary(const json& results) {
    std::string out;
    for (const StageProblem& p : stageProblems(results)) {
        out += (out.empty() ? "" : "; ") + p.stage + ": " + p.status;
        if (severity(p.status) <= 3 && !p.message.empty()) out += " (" + p.message + ")";
    }
    return out;
}

std::string gradebookCsv(const std::vector<json>& reports) {
    std::vector<std::string> stages;  // every stage of any report, in the order they first appear
    for (const json& r : reports)
        for (const json& s : html::array(r, "stages"))
            if (std::find(stages.begin(), stages.end(), html::text(s, "stage")) == stages.end())
                stages.push_back(html::text(s, "stage"));
    std::string csv = "name,score,max_score";
    for (const std::string& stage : stages) csv += "," + csvCell(stage);
    csv += ",problems\n";
    for (const json& r : reports) {
        char total[64];
        std::snprintf(total, sizeof total, "%.2f,%.2f", html::number(r, "score").value_or(0.0),
                      html::number(r, "max_score").value_or(0.0));
        csv += csvCell(html::text(r, "name")) + "," + total;
        for (const std::string& stage : stages) {
            const json* s = findStage(r, stage);
            char score[32] = "";
            if (s) std::snprintf(score, sizeof score, "%.2f", html::number(*s, "score").value_or(0.0));
            csv += std::string(",") + score;
        }
        std::string problems = problemsSummary(r);  // worst first (html_report.h)
        if (html::text(r, "status") == "error")
            problems = "not graded: " + html::text(r, "message");
        csv += "," + csvCell(problems) + "\n";
    }
    return csv;
}

// Under the table: where the similarity report is (voxlab grade --batch
// writes it beside this page), or why there is none.
std::string similarityNote(const json& gradebook) {
    if (!gradebook.is_object() || !gradebook.contains("similarity") || !gradebook["similarity"].is_object()) return "";
    const json& s = gradebook["similarity"];
    std::string text;
    if (s.value("off", false)) {
        text = "Similar code: not compared (<code>--similarity-threshold off</code>).";
    } else if (s.contains("error")) {
        text = "Similar code: no report (" + html::escape(html::text(s, "error")) + ").";
    } else {
        const std::string page = html::text(s, "page"), summary = html::text(s, "summary");
        text = "Similar code across the class, evidence for you to judge: <a href=\"" + html::escape(page) + "\">" +
               html::escape(page) + "</a>" + (summary.empty() ? "" : " (" + html::escape(summary) + ")") + ".";
    }
    return "<p class=\"legend similarity\">" + text + "</p>";
}

std::string classHtmlReportPage(const json& gradebook) {
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
    body += "</header>\n<main class=\"class\"><section class=\"card wide-table\"><table class=\"gradebook sortable\">"
            "<thead><tr><th class=\"who\">Submission <span class=\"sub\">and what went wrong</span></th>"
            "<th class=\"num\">Total</th>";
    // Stage names run upwards so that fifteen stages fit a laptop's width.
    for (const StageColumn& column : columns) {
        const std::string tip = column.title.empty() ? column.stage : column.title + " (" + column.stage + ")";
        body += "<th class=\"num stage-col\" title=\"" + html::escape(tip) + "\"><span class=\"up\">" +
                html::escape(column.stage) + "</span>";
        if (column.maxScore) body += "<div class=\"sub\">/ " + html::formatNumber(*column.maxScore, 2) + "</div>";
        body += "</th>";
    }
    body += "</tr></thead><tbody>\n" + rows + "</tbody>";
    if (totals.count > 0) {
        body += "<tfoot><tr><td>Mean</td><td class=\"num\">" + html::formatNumber(totals.sum / totals.count, 2) +
                "</td>";
        for (const StageColumn& column : columns)
            body += "<td class=\"num\">" +
                    (column.count ? html::formatNumber(column.sum / column.count, 2) : "\u2013") + "</td>";
        body += "</tr></tfoot>";
    }
    body += "</table>" + similarityNote(gradebook) + "<p class=\"legend\">Under each name, what went wrong, worst first: compile errors, crashes, "
            "time-outs and errors with their message, then failed and unfinished (not implemented) stages. A cell "
            "names its stage's problem under the score (\u2013: nothing handed in); hover over it for the stage's "
            "message. Stages worth no "
            "points (the worked example) have no column. Click a column heading to sort by it.</p></section></main>\n"
            "<footer>Written by voxlab grade. Each name links to that submission's report.</footer>\n";

    return html::page(title, body, html::sortableTableScript);
}

void writeClassHtmlReport(const json& gradebook, const std::string& dir) {
    writeFileAtomically((std::filesystem::path(dir) / "index.html").string(), classHtmlReportPage(gradebook));
}

}  // namespace voxlab
