// voxlab grader: Gradescope's results.json and the terminal summary.
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "../report/html_text.h"
#include "voxlab/grader.h"
#include "voxlab/untrusted_text.h"

namespace voxlab {

using nlohmann::json;

namespace {

// `s` (valid UTF-8) in `width` columns: cut at a character's start with "~",
// or padded with spaces (counted in characters).
std::string pad(std::string s, std::size_t width) {
    std::size_t characters = 0, cut = s.size();
    for (std::size_t i = 0; i < s.size(); ++i) {
        if ((static_cast<unsigned char>(s[i]) & 0xC0) == 0x80) continue;
        if (characters == width - 1 && cut == s.size()) cut = i;
        ++characters;
    }
    if (characters > width) return s.substr(0, cut) + "~";
    return s + std::string(width - characters, ' ');
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
    const json* scene = nullptr;  // the report's scene this test is, if it is one
};

// ---------------------------------------------------------------------------
// Images in results.json: Gradescope shows nothing but this file, so a
// failed scene's test carries its images as data: URIs in HTML output.

std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t v = 0;
        for (std::size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? std::uint8_t(bytes[i + k]) : 0u);
        for (std::size_t k = 0; k < 4; ++k) out += k <= n ? digits[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

void appendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}

struct EmbeddedImage {
    std::string uri;  // data:image/png;base64,...; empty when the file could not be read
    int width = 0, height = 0;
};

// The PNG at `path` as a data: URI, shrunk by a whole factor (averaging
// each block of pixels) until its longer side is at most kResultsImageSide.
EmbeddedImage embedPng(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels = stbi_load(path.c_str(), &w, &h, &channels, 3);
    if (!pixels) return {};
    const int f = (std::max(w, h) + kResultsImageSide - 1) / kResultsImageSide;
    const int ow = std::max(1, w / f), oh = std::max(1, h / f);
    std::vector<unsigned char> out(std::size_t(ow) * oh * 3);
    for (int y = 0; y < oh; ++y)
        for (int x = 0; x < ow; ++x)
            for (int c = 0; c < 3; ++c) {
                int sum = 0;
                for (int dy = 0; dy < f; ++dy)
                    for (int dx = 0; dx < f; ++dx) sum += pixels[(std::size_t(y * f + dy) * w + (x * f + dx)) * 3 + c];
                out[(std::size_t(y) * ow + x) * 3 + c] = (unsigned char)((sum + f * f / 2) / (f * f));
            }
    stbi_image_free(pixels);
    std::string png;
    if (!stbi_write_png_to_func(appendBytes, &png, ow, oh, 3, out.data(), ow * 3) || png.empty()) return {};
    return {"data:image/png;base64," + base64(png), ow, oh};
}

// Plain text as HTML: escaped, lines kept.
std::string htmlLines(const std::string& text) {
    std::string out;
    for (std::size_t start = 0; start <= text.size();) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        out += (start ? "<br>" : "") + html::escape(text.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

// A failed scene's output with its expected image, the student's and the
// difference map, shown at twice their size; nothing changes when they are
// not all readable or do not fit in what is left of *budget.
enum class Embedded { Yes, Unreadable, OverBudget };

Embedded addSceneImages(json& entry, const json& scene, const std::string& reportDir, std::size_t* budget) {
    const json& images = html::object(scene, "images");
    const char* keys[] = {"reference", "submission", "difference"};
    const char* captions[] = {"expected", "yours", "difference (red: pixels over the bound)"};
    EmbeddedImage embedded[3];
    std::size_t size = 0;
    for (int i = 0; i < 3; ++i) {
        const std::string path = html::text(images, keys[i]);
        if (path.empty()) return Embedded::Unreadable;
        embedded[i] = embedPng((std::filesystem::path(reportDir) / path).string());
        if (embedded[i].uri.empty()) return Embedded::Unreadable;
        size += embedded[i].uri.size();
    }
    if (size > *budget) return Embedded::OverBudget;
    *budget -= size;
    std::string out = "<p>" + htmlLines(entry["output"].get<std::string>()) + "</p>\n<p>";
    for (const EmbeddedImage& image : embedded)
        out += "<img src=\"" + image.uri + "\" width=\"" + std::to_string(2 * image.width) + "\" height=\"" +
               std::to_string(2 * image.height) + "\" style=\"image-rendering: pixelated\" alt=\"\"> ";
    out += "</p>\n<p>Left to right: " + std::string(captions[0]) + ", " + captions[1] + ", " + captions[2] + ".</p>";
    entry["output"] = out;
    entry["output_format"] = "html";
    return Embedded::Yes;
}

// Embeds the images of failed scenes (see grader.h) while the budget
// lasts: the first failed scene of each stage, then the others, in report
// order; a stage that is not implemented yet (its images show a stub) after
// all the others.
void addImages(std::vector<std::vector<Test>>& stages, const std::vector<bool>& unfinished,
               const std::string& reportDir) {
    std::size_t budget = kResultsImageBudget;
    std::vector<Test*> tiers[4];  // first of a stage, the rest; the same for unfinished stages
    for (std::size_t s = 0; s < stages.size(); ++s) {
        bool seen = false;
        for (Test& t : stages[s]) {
            if (!t.scene || t.scene->value("status", "") == "passed") continue;
            if (!html::object(*t.scene, "images").contains("submission")) continue;
            tiers[(unfinished[s] ? 2 : 0) + (seen ? 1 : 0)].push_back(&t);
            seen = true;
        }
    }
    std::vector<Test*> order;
    for (const std::vector<Test*>& tier : tiers) order.insert(order.end(), tier.begin(), tier.end());
    for (Test* t : order)
        if (addSceneImages(t->entry, *t->scene, reportDir, &budget) == Embedded::OverBudget)
            t->entry["output"] = t->entry["output"].get<std::string>() +
                                 "\n(Images left out: results.json carries at most " +
                                 std::to_string(kResultsImageBudget >> 10) + " KiB of them; the full report has all.)";
}

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
                         const std::string& visibility, const json* scene) {
        tests.push_back({{{"name", name},
                          {"status", item.value("status", "") == "passed" ? "passed" : "failed"},
                          {"output", output},
                          {"visibility", visibility}},
                         item.value("max_score", 0.0),
                         item.value("score", 0.0),
                         scene});
    };
    for (const char* kind : {"scenes", "checks"})
        for (const json& item : html::array(stage, kind)) {  // a reference: scene tests point to their item
            std::string output = item.value("message", "");
            if (!stageNote.empty()) output += "\nStage: " + stageNote;
            const std::string setup = html::text(item, "setup"), file = html::text(item, "scene_file");
            if (!setup.empty()) output += "\nScene" + (file.empty() ? "" : " " + file) + ": " + setup;
            const std::string inputs = html::checkInputsText(html::object(item, "inputs"));
            if (!inputs.empty() && item.value("status", "") != "passed") output += "\nInputs: " + inputs;
            for (const json& ex : html::array(item, "examples"))
                output += "\n  " + (ex.is_string() ? ex.get<std::string>()
                                                   : ex.dump(-1, ' ', false, json::error_handler_t::replace));
            const std::string visibility =
                item.value("visibility", item.value("hidden", false) ? "after_due_date" : "visible");
            add(title + ": " + item.value("name", "?"), item, output, visibility,
                std::string(kind) == "scenes" ? &item : nullptr);
        }
    if (!tests.empty() && stage.contains("all_pass") && stage["all_pass"].value("max_score", 0.0) > 0.0)
        add(title + ": every scene and check passes", stage["all_pass"], stage["all_pass"].value("message", ""),
            "visible", nullptr);
    if (tests.empty()) {
        std::string output = stage.value("message", "");
        if (stage.contains("log")) output += "\n\n" + stage["log"].get<std::string>();
        add(title, {{"status", "failed"}, {"max_score", stage.value("max_score", 0.0)}, {"score", stage.value("score", 0.0)}},
            output, "visible", nullptr);
    }
    // Exact sums: the tests' points add up to the stage's, rounded once.
    std::vector<double> maxima, scores;
    for (const Test& t : tests) maxima.push_back(t.maxScore), scores.push_back(t.score);
    const std::vector<long long> maxCents = apportion(maxima, cents(stage.value("max_score", 0.0)));
    // The items with full marks (or the others) share `total` cents by their
    // scores, none above its rounded maximum; returns what they got.
    std::vector<long long> scoreCents(tests.size());
    const auto share = [&](bool fullMarks, long long total) {
        std::vector<double> values;
        std::vector<long long> caps;
        std::vector<std::size_t> index;
        for (std::size_t i = 0; i < tests.size(); ++i)
            if ((scores[i] >= maxima[i] - 1e-9) == fullMarks)
                values.push_back(scores[i]), caps.push_back(maxCents[i]), index.push_back(i);
        const std::vector<long long> got = apportion(values, total, &caps);
        long long sum = 0;
        for (std::size_t k = 0; k < got.size(); ++k) scoreCents[index[k]] = got[k], sum += got[k];
        return sum;
    };
    // An item with full marks shows its full (rounded) points, unless the
    // maxima's rounding gave the full-mark items more than the stage scored
    // (three items of 4/3 out of 10: 1.34 + 1.34 + 1.33 > 4.00): then they
    // share the stage's score, a cent below their maximum at worst. The
    // others share what is left.
    const long long stageCents = cents(stage.value("score", 0.0));
    long long fullCaps = 0;
    for (std::size_t i = 0; i < tests.size(); ++i)
        if (scores[i] >= maxima[i] - 1e-9) fullCaps += maxCents[i];
    const long long full = share(true, std::min(fullCaps, stageCents));
    share(false, std::max(0LL, stageCents - full));
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
json gradescopeResults(const json& report, const std::string& reportDir) {
    json tests = json::array();
    long long total = 0;
    std::vector<std::vector<Test>> stages;
    std::vector<bool> unfinished;
    for (const json& stage : html::array(report, "stages")) {
        stages.push_back(stageTests(stage));
        unfinished.push_back(html::text(stage, "status") == "not_implemented");
    }
    if (!reportDir.empty()) addImages(stages, unfinished, reportDir);
    for (std::vector<Test>& stage : stages)
        for (Test& t : stage) {
            total += cents(t.entry["score"].get<double>());
            tests.push_back(std::move(t.entry));
        }
    double score = double(total) / 100.0;
    char summary[200];
    std::snprintf(summary, sizeof summary, "voxlab grader: %.2f of %.2f points. The full report with images is "
                  "index.html in the report folder.", score, report.value("max_score", 0.0));
    std::string output = summary;
    if (!reportDir.empty())
        output += "\nA scene that did not pass shows the expected image, yours and their difference (up to " +
                  std::to_string(kResultsImageBudget >> 10) + " KiB of images in all).";
    if (report.contains("late")) {
        score = double(cents(score * report["late"].value("factor", 1.0))) / 100.0;
        std::snprintf(summary, sizeof summary, "; total %.2f.", score);
        output += "\nLate: " + report["late"].value("message", "") + summary;
    }
    if (report.contains("layout_note")) output += "\nUpload: " + report.value("layout_note", "") + ".";
    if (html::text(report, "status") == "error") output += "\nNot graded: " + html::text(report, "message") + ".";
    return {{"score", score}, {"output", output}, {"visibility", "visible"}, {"stdout_visibility", "visible"},
            {"tests", tests}};
}

std::string summaryTable(const json& report) {
    std::string out = pad("stage", 15) + pad("status", 17) + pad("score", 13) + "message\n";
    out += std::string(100, '-') + "\n";
    for (const json& stage : html::array(report, "stages")) {
        char score[32];
        std::snprintf(score, sizeof score, "%5.2f / %-5.4g", html::number(stage, "score").value_or(0.0),
                      html::number(stage, "max_score").value_or(0.0));
        out += pad(terminalLine(html::text(stage, "stage"), 64), 15) + pad(terminalLine(html::text(stage, "status"), 64), 17) +
               pad(score, 13) + terminalLine(html::text(stage, "message")) + "\n";
        // Each scene that reached the starter code's stubs, and which (a stage
        // not yet implemented itself reaches its own in every scene: no list).
        for (const json& scene : html::array(stage, "scenes")) {
            if (html::text(stage, "status") == "not_implemented") break;
            std::string reached;  // "gradient/gradient_central(), shading/phong()"
            for (const json& stub : html::array(scene, "not_implemented_reached"))
                if (stub.is_string()) reached += (reached.empty() ? "" : ", ") + stub.get<std::string>() + "()";
            if (reached.empty()) continue;
            out += pad("", 15) + terminalLine("  " + html::text(scene, "name") + ": " +
                                              (html::text(scene, "status") == "blocked" ? "blocked, " : "") +
                                              "reached not yet implemented " + reached) + "\n";
        }
    }
    out += std::string(100, '-') + "\n";
    char total[96];
    std::snprintf(total, sizeof total, "total %.2f / %.4g points", html::number(report, "score").value_or(0.0),
                  html::number(report, "max_score").value_or(0.0));
    return out + pad("", 15) + total + "\n";
}

}  // namespace voxlab
