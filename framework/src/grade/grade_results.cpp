// voxlab grader: Gradescope's results.json and the terminal summary.
#include <cmath>
#include <cstdio>

#include "voxlab/grader.h"

namespace voxlab {

using nlohmann::json;

namespace {

double rounded(double x) { return std::round(x * 100.0) / 100.0; }

std::string pad(std::string s, std::size_t width) {
    if (s.size() > width) s = s.substr(0, width - 1) + "~";
    return s + std::string(width - s.size(), ' ');
}

}  // namespace

// Gradescope's autograder format
// (https://gradescope-autograders.readthedocs.io/en/latest/specs/): a total
// `score` and one entry of `tests` per graded item, each with name, score,
// max_score, status ("passed"/"failed"), output and visibility. A stage
// that produced no items (it did not compile, or timed out before the
// first scene) is one failed test holding its message and log.
json gradescopeResults(const json& report) {
    json tests = json::array();
    for (const json& stage : report.value("stages", json::array())) {
        const std::string title = stage.value("title", stage.value("stage", "?"));
        std::string stageNote = stage.value("status", "") == "passed" || stage.value("status", "") == "example"
                                    ? ""
                                    : stage.value("message", "");
        for (const json& hint : stage.value("hints", json::array()))
            if (hint.is_string()) stageNote += "\nHint: " + hint.get<std::string>();
        bool any = false;
        for (const char* kind : {"scenes", "checks"})
            for (const json& item : stage.value(kind, json::array())) {
                any = true;
                std::string output = item.value("message", "");
                if (!stageNote.empty()) output += "\nStage: " + stageNote;
                for (const json& ex : item.value("examples", json::array())) output += "\n  " + ex.get<std::string>();
                tests.push_back({{"name", title + ": " + item.value("name", "?")},
                                 {"score", rounded(item.value("score", 0.0))},
                                 {"max_score", rounded(item.value("max_score", 0.0))},
                                 {"status", item.value("status", "") == "passed" ? "passed" : "failed"},
                                 {"output", output},
                                 {"visibility", item.value("hidden", false) ? "after_due_date" : "visible"}});
            }
        if (any && stage.contains("all_pass") && stage["all_pass"].value("max_score", 0.0) > 0.0) {
            const json& bonus = stage["all_pass"];
            tests.push_back({{"name", title + ": every scene and check passes"},
                             {"score", rounded(bonus.value("score", 0.0))},
                             {"max_score", rounded(bonus.value("max_score", 0.0))},
                             {"status", bonus.value("status", "") == "passed" ? "passed" : "failed"},
                             {"output", bonus.value("message", "")},
                             {"visibility", "visible"}});
        }
        if (!any) {
            std::string output = stage.value("message", "");
            if (stage.contains("log")) output += "\n\n" + stage["log"].get<std::string>();
            tests.push_back({{"name", title},
                             {"score", rounded(stage.value("score", 0.0))},
                             {"max_score", rounded(stage.value("max_score", 0.0))},
                             {"status", "failed"},
                             {"output", output},
                             {"visibility", "visible"}});
        }
    }
    char summary[160];
    std::snprintf(summary, sizeof summary, "voxlab grader: %.2f of %.2f points. The full report with images is "
                  "index.html in the report folder.", report.value("score", 0.0), report.value("max_score", 0.0));
    return {{"score", rounded(report.value("score", 0.0))}, {"output", summary}, {"visibility", "visible"},
            {"stdout_visibility", "visible"}, {"tests", tests}};
}

std::string summaryTable(const json& report) {
    std::string out = pad("stage", 15) + pad("status", 17) + pad("score", 13) + "message\n";
    out += std::string(100, '-') + "\n";
    for (const json& stage : report.value("stages", json::array())) {
        char score[32];
        std::snprintf(score, sizeof score, "%5.2f / %-5.4g", stage.value("score", 0.0), stage.value("max_score", 0.0));
        out += pad(stage.value("stage", "?"), 15) + pad(stage.value("status", "?"), 17) + pad(score, 13) +
               stage.value("message", "") + "\n";
    }
    out += std::string(100, '-') + "\n";
    char total[96];
    std::snprintf(total, sizeof total, "total %.2f / %.4g points", report.value("score", 0.0),
                  report.value("max_score", 0.0));
    return out + pad("", 15) + total + "\n";
}

}  // namespace voxlab
