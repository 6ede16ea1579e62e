// voxlab grader: Gradescope's results.json and the terminal summary.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "voxlab/grader.h"

namespace voxlab {

using nlohmann::json;

namespace {

std::string pad(std::string s, std::size_t width) {
    if (s.size() > width) s = s.substr(0, width - 1) + "~";
    return s + std::string(width - s.size(), ' ');
}

// Hundredths of a point, as Gradescope shows them.
long long cents(double x) { return std::llround(x * 100.0); }

// Rounds `values` to hundredths so that they add up to exactly `total`
// hundredths (the largest-remainder method): each value moves by less than
// one hundredth, and the ones nearest to rounding up go up first, within
// each value's cap when one is given.
std::vector<long long> apportion(const std::vector<double>& values, long long total,
                                 const std::vector<long long>* caps = nullptr) {
    std::vector<long long> out(values.size());
    std::vector<std::pair<double, std::size_t>> remainders;
    long long sum = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        out[i] = (long long)std::floor(values[i] * 100.0 + 1e-9);
        if (caps) out[i] = std::min(out[i], (*caps)[i]);
        sum += out[i];
        remainders.push_back({values[i] * 100.0 - double(out[i]), i});
    }
    std::stable_sort(remainders.begin(), remainders.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    for (std::size_t k = 0; sum < total && !remainders.empty(); k = (k + 1) % remainders.size()) {
        const std::size_t i = remainders[k].second;
        if (caps && out[i] >= (*caps)[i]) {
            if (std::all_of(remainders.begin(), remainders.end(),
                            [&](const auto& r) { return out[r.second] >= (*caps)[r.second]; }))
                break;
            continue;
        }
        ++out[i];
        ++sum;
    }
    // Too much already (rounding elsewhere took a hundredth): the values
    // nearest to rounding down give it back.
    for (auto it = remainders.rbegin(); sum > total && it != remainders.rend(); ++it)
        if (out[it->second] > 0) --out[it->second], --sum;
    return out;
}

struct Test {
    json entry;
    double maxScore, score;
};

// The tests of one stage: one per scene and check, the all-pass share, or
// one for a stage that produced no items (it did not compile, or timed out
// before its first scene), holding its message and log.
std::vector<Test> stageTests(const json& stage) {
    const std::string title = stage.value("title", stage.value("stage", "?"));
    std::string stageNote = stage.value("status", "") == "passed" || stage.value("status", "") == "example"
                                ? ""
                                : stage.value("message", "");
    for (const json& hint : stage.value("hints", json::array()))
        if (hint.is_string()) stageNote += "\nHint: " + hint.get<std::string>();
    std::vector<Test> tests;
    const auto add = [&](const std::string& name, const json& item, const std::string& output,
                         const std::string& visibility) {
        tests.push_back({{{"name", name},
                          {"status", item.value("status", "") == "passed" ? "passed" : "failed"},
                          {"output", output},
                          {"visibility", visibility}},
                         item.value("max_score", 0.0),
                         item.value("score", 0.0)});
    };
    for (const char* kind : {"scenes", "checks"})
        for (const json& item : stage.value(kind, json::array())) {
            std::string output = item.value("message", "");
            if (!stageNote.empty()) output += "\nStage: " + stageNote;
            for (const json& ex : item.value("examples", json::array())) output += "\n  " + ex.get<std::string>();
            const std::string visibility =
                item.value("visibility", item.value("hidden", false) ? "after_due_date" : "visible");
            add(title + ": " + item.value("name", "?"), item, output, visibility);
        }
    if (!tests.empty() && stage.contains("all_pass") && stage["all_pass"].value("max_score", 0.0) > 0.0)
        add(title + ": every scene and check passes", stage["all_pass"], stage["all_pass"].value("message", ""),
            "visible");
    if (tests.empty()) {
        std::string output = stage.value("message", "");
        if (stage.contains("log")) output += "\n\n" + stage["log"].get<std::string>();
        add(title, {{"status", "failed"}, {"max_score", stage.value("max_score", 0.0)}, {"score", stage.value("score", 0.0)}},
            output, "visible");
    }
    // Exact sums: the tests' points add up to the stage's, rounded once.
    std::vector<double> maxima, scores;
    for (const Test& t : tests) maxima.push_back(t.maxScore), scores.push_back(t.score);
    const std::vector<long long> maxCents = apportion(maxima, cents(stage.value("max_score", 0.0)));
    // An item with full marks shows its full (rounded) points; the others
    // share what is left of the stage's score.
    std::vector<long long> scoreCents(tests.size()), caps;
    std::vector<double> partial;
    std::vector<std::size_t> partialIndex;
    long long full = 0;
    for (std::size_t i = 0; i < tests.size(); ++i)
        if (scores[i] >= maxima[i] - 1e-9) {
            scoreCents[i] = maxCents[i];
            full += maxCents[i];
        } else {
            partial.push_back(scores[i]);
            partialIndex.push_back(i);
            caps.push_back(maxCents[i]);
        }
    const std::vector<long long> rest =
        apportion(partial, std::max(0LL, cents(stage.value("score", 0.0)) - full), &caps);
    for (std::size_t k = 0; k < rest.size(); ++k) scoreCents[partialIndex[k]] = rest[k];
    for (std::size_t i = 0; i < tests.size(); ++i) {
        tests[i].entry["max_score"] = double(maxCents[i]) / 100.0;
        tests[i].entry["score"] = double(scoreCents[i]) / 100.0;
    }
    return tests;
}

}  // namespace

// Gradescope's autograder format
// (https://gradescope-autograders.readthedocs.io/en/latest/specs/): a total
// `score` and one entry of `tests` per graded item, each with name, score,
// max_score, status ("passed"/"failed"), output and visibility (from the
// assignment file: assignment.h). Each stage's tests add up to its score
// rounded to hundredths, and the total is their sum (times the late factor
// when there is one, which the output states).
json gradescopeResults(const json& report) {
    json tests = json::array();
    long long total = 0;
    for (const json& stage : report.value("stages", json::array()))
        for (Test& t : stageTests(stage)) {
            total += cents(t.entry["score"].get<double>());
            tests.push_back(std::move(t.entry));
        }
    double score = double(total) / 100.0;
    char summary[200];
    std::snprintf(summary, sizeof summary, "voxlab grader: %.2f of %.2f points. The full report with images is "
                  "index.html in the report folder.", score, report.value("max_score", 0.0));
    std::string output = summary;
    if (report.contains("late")) {
        score = double(cents(score * report["late"].value("factor", 1.0))) / 100.0;
        std::snprintf(summary, sizeof summary, "; total %.2f.", score);
        output += "\nLate: " + report["late"].value("message", "") + summary;
    }
    if (report.contains("layout_note")) output += "\nUpload: " + report.value("layout_note", "") + ".";
    return {{"score", score}, {"output", output}, {"visibility", "visible"}, {"stdout_visibility", "visible"},
            {"tests", tests}};
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
