// voxlab: one graded submission as an HTML page (schema in html_report.h).
//
// The page reads top to bottom the way a student asks: how did I do (total
// and a table of stages), then per stage what went wrong (message, compiler
// log), then per scene the images side by side with the metrics that decided
// the score, then the function checks with the cases that failed.
#include "voxlab/html_report.h"

#include <stb_image.h>

#include <filesystem>
#include <set>
#include <sstream>

#include "html_text.h"
#include "voxlab/atomic_file.h"

namespace voxlab {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct ImageSlot {
    const char* key;
    const char* caption;
    const char* hint;
};

// The grader's images (grading.h: compareForGrading); hints become tooltips.
const ImageSlot imageSlots[] = {
    {"reference", "Reference", "rendered by the reference solution"},
    {"submission", "Submission", "rendered by this submission"},
    {"flip", "FLIP error", "perceived difference (Andersson et al. 2020): black none, yellow large"},
    {"difference", "Difference", "per-pixel |difference|, amplified; red where a pixel is over the bound"},
};

// "2026-11-22T07:10:00Z" -> "2026-11-22 07:10 UTC"; anything else as given.
std::string readableTime(const std::string& iso) {
    if (iso.size() == 20 && iso[10] == 'T' && iso[19] == 'Z')
        return iso.substr(0, 10) + " " + iso.substr(11, 5) + " UTC";
    return iso;
}

// Element ids unique within the page, readable in the address bar.
class IdMaker {
public:
    std::string make(const std::string& prefix, const std::string& name) {
        std::string id = prefix + html::token(name);
        for (int n = 2; !used_.insert(id).second; ++n) id = prefix + html::token(name) + "-" + std::to_string(n);
        return id;
    }

private:
    std::set<std::string> used_;
};

// A compiler log with error and warning lines marked.
std::string logBlock(const std::string& log) {
    std::istringstream lines(log);
    std::string out = "<pre class=\"log\">", line;
    while (std::getline(lines, line)) {
        const bool isError = line.find("error") != std::string::npos;
        const bool isWarning = !isError && line.find("warning") != std::string::npos;
        if (isError) out += "<span class=\"err\">" + html::escape(line) + "</span>\n";
        else if (isWarning) out += "<span class=\"warn\">" + html::escape(line) + "</span>\n";
        else out += html::escape(line) + "\n";
    }
    return out + "</pre>\n";
}

// The scene's images at twice their size, or placeholders saying why not.
// Sets messageShown when the scene's message fills the placeholder.
std::string figures(const json& scene, const std::string& reportDir, bool& messageShown) {
    const json& images = html::object(scene, "images");
    struct Found { std::string path; int width = 0, height = 0; };
    Found found[4];
    int shownWidth = 0, shownHeight = 0, present = 0;
    for (int i = 0; i < 4; ++i) {
        const std::string path = html::text(images, imageSlots[i].key);
        int w = 0, h = 0, channels = 0;
        if (path.empty() || !fs::is_regular_file(fs::path(reportDir) / path)) continue;
        if (stbi_info((fs::path(reportDir) / path).string().c_str(), &w, &h, &channels)) {
            shownWidth = 2 * w, shownHeight = 2 * h;  // pixelated, so each pixel is visible
        }
        found[i] = {path, w, h};
        ++present;
    }
    const std::string message = html::text(scene, "message");
    if (present == 0) {
        messageShown = true;
        const std::string why = message.empty() ? "No images were written for this scene." : message;
        return "<div class=\"placeholder wide\">" + html::escape(why) + "</div>\n";
    }
    // Placeholders take the size of the images beside them.
    const std::string sizeStyle = shownWidth > 0
        ? " style=\"width:" + std::to_string(shownWidth) + "px;height:" + std::to_string(shownHeight) + "px\"" : "";
    // Without the submission's image, its slot says why (the scene's message) and the comparisons have none.
    const bool noSubmission = found[1].path.empty();
    messageShown = noSubmission && !message.empty();
    std::string out = "<div class=\"figures\">\n";
    for (int i = 0; i < 4; ++i) {
        out += "<figure title=\"" + html::escape(imageSlots[i].hint) + "\">";
        if (found[i].path.empty()) {
            std::string why = "not written", kind = "placeholder";
            if (i == 1 && !message.empty()) why = message, kind = "placeholder why";
            else if (i > 1 && noSubmission) why = "no submission image to compare";
            out += "<div class=\"" + kind + "\"" + sizeStyle + ">" + html::escape(why) + "</div>";
        } else {
            const std::string src = html::urlPath(found[i].path);
            std::string size;
            if (found[i].width > 0) {
                size = " width=\"" + std::to_string(2 * found[i].width) + "\" height=\"" +
                       std::to_string(2 * found[i].height) + "\"";
            }
            out += "<a href=\"" + src + "\"><img src=\"" + src + "\"" + size + " alt=\"" +
                   html::escape(std::string(imageSlots[i].caption) + " image") + "\"></a>";
        }
        out += "<figcaption>" + std::string(imageSlots[i].caption) + "</figcaption></figure>\n";
    }
    return out + "</div>\n";
}

enum class Verdict { Shown, Pass, Fail };

// One metric as a tile: its name, its value, and the bound it must meet (none for display-only metrics).
std::string metricTile(const std::string& label, const std::string& value, const std::string& bound, Verdict verdict) {
    const char* tileClass = verdict == Verdict::Pass ? "ok" : verdict == Verdict::Fail ? "bad" : "shown";
    const char* mark = verdict == Verdict::Pass ? " \u2713" : verdict == Verdict::Fail ? " \u2717" : "";
    return "<div class=\"metric " + std::string(tileClass) + "\"><div class=\"m-label\">" + label +
           "</div><div class=\"m-value\">" + value + mark + "</div><div class=\"m-bound\">" +
           (bound.empty() ? std::string("for information") : "must be " + bound) + "</div></div>\n";
}

Verdict judge(bool hasBound, bool passes) {
    return !hasBound ? Verdict::Shown : passes ? Verdict::Pass : Verdict::Fail;
}

// Each metric with its bound and whether it passes (grading.h states the rules).
std::string metricTiles(const json& scene) {
    const json& metrics = html::object(scene, "metrics");
    const json& tolerance = html::object(scene, "tolerance");
    if (metrics.empty()) return {};
    std::string tiles;
    const auto percent = [](double fraction) { return html::formatNumber(fraction * 100.0, 3) + " %"; };

    const auto threshold = html::number(tolerance, "max_difference");
    if (auto over = html::number(metrics, "fraction_over")) {
        const auto bound = html::number(tolerance, "max_fraction");
        const std::string label = threshold ? "Pixels off by &gt; " + html::formatNumber(*threshold, 2) + "/255"
                                            : std::string("Pixels over the threshold");
        tiles += metricTile(label, percent(*over), bound ? "\u2264 " + percent(*bound) : "",
                           judge(bool(bound), bound && *over <= *bound));
    }
    if (auto cluster = html::number(metrics, "largest_cluster")) {
        const auto bound = html::number(tolerance, "max_cluster");
        const auto level = html::number(tolerance, "cluster_difference");
        const std::string label = level ? "Largest patch off by &gt; " + html::formatNumber(*level, 2) + "/255"
                                        : std::string("Largest badly wrong patch");
        tiles += metricTile(label, html::formatNumber(*cluster, 0) + " px",
                           bound ? "\u2264 " + html::formatNumber(*bound, 0) + " px" : "",
                           judge(bool(bound), bound && *cluster <= *bound));
    }
    if (auto largest = html::number(metrics, "max_difference"))
        tiles += metricTile("Largest difference", html::formatNumber(*largest, 1) + "/255", "", Verdict::Shown);
    if (auto ssim = html::number(metrics, "ssim")) {
        const auto bound = html::number(tolerance, "min_ssim");
        tiles += metricTile("SSIM, mean", html::formatNumber(*ssim, 4),
                           bound ? "\u2265 " + html::formatNumber(*bound, 4) : "",
                           judge(bool(bound), bound && *ssim >= *bound));
    }
    if (auto worst = html::number(metrics, "ssim_min"))
        tiles += metricTile("SSIM, worst window", html::formatNumber(*worst, 3), "", Verdict::Shown);
    if (auto flip = html::number(metrics, "flip_mean")) {
        const auto bound = html::number(tolerance, "max_flip");
        tiles += metricTile("FLIP, mean", html::formatNumber(*flip, 4),
                           bound ? "\u2264 " + html::formatNumber(*bound, 4) : "",
                           judge(bool(bound), bound && *flip <= *bound));
    }
    if (auto flipMax = html::number(metrics, "flip_max"))
        tiles += metricTile("FLIP, max", html::formatNumber(*flipMax, 3), "", Verdict::Shown);
    if (metrics.contains("psnr")) {
        // null means infinite: the images are identical.
        const auto psnr = html::number(metrics, "psnr");
        if (psnr || metrics["psnr"].is_null())
            tiles += metricTile("PSNR", psnr ? html::formatNumber(*psnr, 1) + " dB" : "\u221e dB", "", Verdict::Shown);
    }
    if (tiles.empty()) return {};
    return "<div class=\"metrics\">\n" + tiles + "</div>\n";
}

std::string sceneBlock(const json& scene, const std::string& reportDir, IdMaker& ids, const std::string& stageId) {
    const std::string name = html::text(scene, "name");
    const std::string message = html::text(scene, "message");
    std::string out = "<div class=\"scene\" id=\"" + ids.make(stageId + "-", name) + "\">\n<div class=\"scene-head\">"
                      "<span class=\"scene-name\">" + html::escape(name) + "</span>" +
                      html::badge(html::text(scene, "status")) + "<span class=\"score\">" +
                      html::escape(html::formatScore(html::number(scene, "score"), html::number(scene, "max_score"))) +
                      "</span></div>\n";
    bool messageShown = false;
    const std::string images = figures(scene, reportDir, messageShown);
    if (!message.empty() && !messageShown) out += "<p class=\"message\">" + html::escape(message) + "</p>\n";
    return out + "<div class=\"scene-body\">\n" + images + metricTiles(scene) + "</div></div>\n";
}

std::string checksTable(const json& checks) {
    std::string out = "<table class=\"checks\"><thead><tr><th>Check</th><th>Status</th><th class=\"num\">Score</th>"
                      "<th>Result</th></tr></thead><tbody>\n";
    for (const json& check : checks) {
        const std::string status = html::text(check, "status");
        const std::string description = html::text(check, "description");
        out += "<tr><td><span class=\"check-name\">" + html::escape(html::text(check, "name")) + "</span>";
        if (!description.empty()) out += "<div class=\"sub\">" + html::escape(description) + "</div>";
        out += "</td><td>" + html::badge(status) + "</td><td class=\"num\">" +
               html::escape(html::formatScore(html::number(check, "score"), html::number(check, "max_score"))) +
               "</td><td>" + html::escape(html::text(check, "message"));
        const json& examples = html::array(check, "examples");
        if (!examples.empty()) {
            out += std::string("<details") + (status == "passed" ? "" : " open") + "><summary>" +
                   std::to_string(examples.size()) + (examples.size() == 1 ? " example" : " examples") +
                   "</summary><ul class=\"examples\">";
            for (const json& example : examples)
                out += "<li><code>" + html::escape(example.is_string() ? example.get<std::string>() : example.dump()) +
                       "</code></li>";
            out += "</ul></details>";
        }
        out += "</td></tr>\n";
    }
    return out + "</tbody></table>\n";
}

std::string stageSection(const json& stage, const std::string& id, const std::string& reportDir, IdMaker& ids) {
    const std::string name = html::text(stage, "stage");
    std::string title = html::text(stage, "title");
    if (title.empty()) title = name;
    const auto score = html::number(stage, "score"), maxScore = html::number(stage, "max_score");
    std::string out = "<section class=\"card stage\" id=\"" + id + "\">\n<div class=\"stage-head\"><h2>" +
                      html::escape(title) + " <span class=\"stage-id\">" + html::escape(name) + "</span></h2>" +
                      html::badge(html::text(stage, "status")) + "<span class=\"score big\">" +
                      html::escape(html::formatScore(score, maxScore)) + "</span></div>\n";
    const std::string message = html::text(stage, "message"), about = html::text(stage, "about");
    if (!message.empty()) out += "<p class=\"message\">" + html::escape(message) + "</p>\n";
    if (!about.empty()) out += "<p class=\"about\">" + html::escape(about) + "</p>\n";
    for (const json& hint : html::array(stage, "hints"))
        if (hint.is_string()) out += "<p class=\"hint\">Hint: " + html::escape(hint.get<std::string>()) + "</p>\n";
    if (auto seconds = html::number(stage, "elapsed_s"))
        out += "<p class=\"sub\">Graded in " + html::formatSeconds(*seconds) + ".</p>\n";
    const std::string log = html::text(stage, "log");
    if (!log.empty())
        out += std::string("<details class=\"log-box\" open><summary>") +
               (html::text(stage, "status") == "compile_error" ? "Compiler log" : "What the stage's process printed") +
               "</summary>" + logBlock(log) + "</details>\n";
    const json& scenes = html::array(stage, "scenes");
    if (!scenes.empty()) {
        out += "<h3>Scenes</h3>\n";
        for (const json& scene : scenes) out += sceneBlock(scene, reportDir, ids, id);
        out += "<p class=\"legend\">FLIP: black means no perceived difference, bright yellow a large one. "
               "Difference: per-pixel |difference|, amplified; red marks pixels over the bound. "
               "Click an image to open it at full size.</p>\n";
    }
    const json& checks = html::array(stage, "checks");
    if (!checks.empty()) out += "<h3>Function checks</h3>\n" + checksTable(checks);
    if (stage.contains("all_pass") && html::number(stage["all_pass"], "max_score").value_or(0.0) > 0.0) {
        const json& bonus = stage["all_pass"];
        out += "<p class=\"sub\">Every scene and check passes: " +
               html::escape(html::formatScore(html::number(bonus, "score"), html::number(bonus, "max_score"))) +
               " (" + html::escape(html::text(bonus, "message")) + ").</p>\n";
    }
    return out + "</section>\n";
}

std::string header(const json& results, const json& stages) {
    std::optional<double> score = html::number(results, "score"), maxScore = html::number(results, "max_score");
    // Without a total, the stages' scores add up to one.
    if ((!score || !maxScore) && !stages.empty()) {
        double sum = 0.0, maxSum = 0.0;
        for (const json& stage : stages) sum += html::number(stage, "score").value_or(0.0),
                                         maxSum += html::number(stage, "max_score").value_or(0.0);
        if (!score) score = sum;
        if (!maxScore) maxScore = maxSum;
    }
    std::string name = html::text(results, "name");
    if (name.empty()) name = "Submission";
    const std::string mode = html::text(results, "mode");
    std::string out = "<header class=\"top\"><div class=\"who\"><div class=\"kicker\">" +
                      std::string(mode == "check" ? "voxlab self-check" : "voxlab grade report") + "</div><h1>" +
                      html::escape(name) + "</h1>";
    const std::string submission = html::text(results, "submission");
    if (!submission.empty()) out += "<div class=\"path\">" + html::escape(submission) + "</div>";
    out += "<dl class=\"meta\">";
    const auto meta = [&out](const char* term, const std::string& value) {
        if (!value.empty()) out += "<div><dt>" + std::string(term) + "</dt><dd>" + html::escape(value) + "</dd></div>";
    };
    meta("Graded", readableTime(html::text(results, "graded_at")));
    // A self-check in the full repository renders its expected images from reference/.
    const std::string against = html::text(results, "against");
    meta("Against", against == "shipped" ? "the shipped golden images" : against == "reference" ? "the reference solution" : "");
    meta("Machine", html::text(results, "machine"));
    std::string isolation;
    if (results.contains("sandbox") && results["sandbox"].is_array())
        for (const json& layer : results["sandbox"])
            if (layer.is_string()) isolation += (isolation.empty() ? "" : ", ") + layer.get<std::string>();
    meta("Isolation", isolation.empty() ? "none on this machine" : isolation);
    if (auto seconds = html::number(results, "elapsed_s")) meta("Time", html::formatSeconds(*seconds));
    out += "</dl></div>\n<div class=\"total\"><div class=\"total-score\">" +
           (score ? html::formatNumber(*score, 2) : std::string("\u2013"));
    if (maxScore) out += "<span class=\"of\"> / " + html::formatNumber(*maxScore, 2) + "</span>";
    out += "</div>";
    if (score && maxScore && *maxScore > 0.0)
        out += "<div class=\"percent\">" + html::formatNumber(100.0 * *score / *maxScore, 1) + " %</div>";
    return out + html::scoreBar(score, maxScore) + "</div></header>\n";
}

std::string summaryTable(const json& stages, const std::vector<std::string>& ids) {
    std::string out = "<section class=\"card\"><h2>Stages</h2><table class=\"summary\"><thead><tr><th>Stage</th>"
                      "<th>Status</th><th class=\"num\">Score</th><th>Message</th></tr></thead><tbody>\n";
    for (std::size_t i = 0; i < stages.size(); ++i) {
        const json& stage = stages[i];
        std::string title = html::text(stage, "title");
        if (title.empty()) title = html::text(stage, "stage");
        const auto score = html::number(stage, "score"), maxScore = html::number(stage, "max_score");
        out += "<tr><td><a href=\"#" + ids[i] + "\">" + html::escape(title) + "</a><div class=\"sub\">" +
               html::escape(html::text(stage, "stage")) + "</div></td><td>" + html::badge(html::text(stage, "status")) +
               "</td><td class=\"num\">" + html::escape(html::formatScore(score, maxScore)) +
               html::scoreBar(score, maxScore) + "</td><td class=\"msg\">" +
               html::escape(html::text(stage, "message")) + "</td></tr>\n";
    }
    return out + "</tbody></table></section>\n";
}

}  // namespace

void writeHtmlReport(const json& results, const std::string& reportDir) {
    const json& stages = html::array(results, "stages");
    IdMaker ids;
    std::vector<std::string> stageIds;
    for (const json& stage : stages) stageIds.push_back(ids.make("stage-", html::text(stage, "stage")));

    std::string body = header(results, stages) + "<main>\n";
    if (!stages.empty()) body += summaryTable(stages, stageIds);
    for (std::size_t i = 0; i < stages.size(); ++i) body += stageSection(stages[i], stageIds[i], reportDir, ids);
    body += "</main>\n<footer>Written by voxlab grade. This folder is self-contained and works offline.</footer>\n";

    const std::string name = html::text(results, "name");
    writeFileAtomically((fs::path(reportDir) / "index.html").string(),
                        html::page((name.empty() ? std::string("Submission") : name) + " \u2013 voxlab report", body, ""));
}

}  // namespace voxlab
