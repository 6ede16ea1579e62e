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

// What the two images of a comparison are called: a self-check compares
// "yours" with "expected", a grade report the submission with the reference.
struct Captions {
    std::string expected, mine;
};

Captions captionsFor(const std::string& mode) {
    return mode == "check" ? Captions{"Expected", "Yours"} : Captions{"Reference", "Submission"};
}

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

// One of a scene's images on disk, with its size in pixels (0 when unknown).
struct SceneImage {
    std::string path;
    int width = 0, height = 0;
    bool present() const { return !path.empty(); }
};

SceneImage findImage(const json& images, const char* key, const std::string& reportDir) {
    const std::string path = html::text(images, key);
    if (path.empty() || !fs::is_regular_file(fs::path(reportDir) / path)) return {};
    SceneImage image{path};
    int channels = 0;
    if (!stbi_info((fs::path(reportDir) / path).string().c_str(), &image.width, &image.height, &channels))
        image.width = image.height = 0;
    return image;
}

// Renders are small (128 px): the comparison shows them magnified by the
// largest whole factor that keeps them within 512 px, pixels kept sharp.
int compareScale(const SceneImage& image) {
    const int side = std::max(image.width, image.height);
    return side > 0 ? std::max(1, 512 / side) : 1;
}

std::string sizeAttributes(const SceneImage& image, int scale) {
    if (image.width <= 0) return "";
    return " width=\"" + std::to_string(scale * image.width) + "\" height=\"" + std::to_string(scale * image.height) +
           "\"";
}

// The expected image under the student's, split by a slider (the script in
// html_report_style.cpp moves the split), with buttons that show either one
// alone and one that enlarges both. The buttons are radio buttons and a
// check box styled by the sheet, so they work without the script.
std::string compareWidget(const SceneImage& expected, const SceneImage& mine, int scale, const Captions& captions,
                          const std::string& id) {
    const SceneImage& base = expected.present() ? expected : mine;
    const bool both = expected.present() && mine.present();
    std::string out = "<div class=\"compare\">", labels;
    if (both) {
        for (const std::string mode : {"split", "expected", "mine"})
            out += "<input type=\"radio\" class=\"v-" + mode + "\" name=\"" + id + "\" id=\"" + id + "-" + mode +
                   "\"" + (mode == "split" ? " checked" : "") + ">";
        labels = "<label class=\"m-expected\" for=\"" + id + "-expected\">" + captions.expected +
                 "</label><label class=\"m-split\" for=\"" + id + "-split\">Slider</label><label class=\"m-mine\" " +
                 "for=\"" + id + "-mine\">" + captions.mine + "</label>";
    }
    out += "<input type=\"checkbox\" class=\"v-zoom\" id=\"" + id + "-zoom\">";
    out += "<div class=\"modes\">" + labels + "<label class=\"m-zoom\" for=\"" + id + "-zoom\">Enlarge</label></div>";
    const int width = base.width > 0 ? scale * base.width : 512;
    out += "<div class=\"stack\" style=\"--w:" + std::to_string(width) + "px\">";
    out += "<img class=\"under\" src=\"" + html::urlPath(base.path) + "\"" + sizeAttributes(base, scale) + " alt=\"" +
           html::escape(expected.present() ? captions.expected : captions.mine) + " image\">";
    if (both) {
        out += "<img class=\"over\" src=\"" + html::urlPath(mine.path) + "\"" + sizeAttributes(mine, scale) +
               " alt=\"" + captions.mine + " image\"><span class=\"divider\"></span>"
               "<input type=\"range\" class=\"slider\" min=\"0\" max=\"100\" value=\"50\" aria-label=\"Split between " +
               captions.expected + " (left) and " + captions.mine + " (right)\">";
        out += "<span class=\"tag left\">" + captions.expected + "</span><span class=\"tag right\">" + captions.mine +
               "</span>";
    }
    out += "</div><div class=\"open\">Open at full size:";
    if (expected.present()) out += " <a href=\"" + html::urlPath(expected.path) + "\">" + captions.expected + "</a>";
    if (both) out += " \u00b7";
    if (mine.present()) out += " <a href=\"" + html::urlPath(mine.path) + "\">" + captions.mine + "</a>";
    return out + "</div></div>\n";
}

// A heat map beside the comparison, or a placeholder of its size saying why not.
std::string mapFigure(const SceneImage& image, int scale, const SceneImage& like, const std::string& caption,
                      const std::string& hint, const std::string& why) {
    std::string out = "<figure title=\"" + html::escape(hint) + "\">";
    if (image.present()) {
        out += "<a href=\"" + html::urlPath(image.path) + "\"><img src=\"" + html::urlPath(image.path) + "\"" +
               sizeAttributes(image, scale) + " alt=\"" + caption + " image\"></a>";
    } else {
        const std::string size = like.width > 0 ? " style=\"width:" + std::to_string(scale * like.width) +
                                                      "px;height:" + std::to_string(scale * like.height) + "px\""
                                                : "";
        out += "<div class=\"placeholder\"" + size + ">" + html::escape(why) + "</div>";
    }
    return out + "<figcaption>" + caption + "</figcaption></figure>";
}

// The scene's images: the comparison of the expected image with the
// submission's, large, and the FLIP and difference maps at half its
// magnification; placeholders say what is missing and why. Sets
// messageShown when the scene's message fills a placeholder.
std::string figures(const json& scene, const std::string& reportDir, const Captions& captions, const std::string& id,
                    bool& messageShown) {
    const json& images = html::object(scene, "images");
    const SceneImage expected = findImage(images, "reference", reportDir);
    const SceneImage mine = findImage(images, "submission", reportDir);
    const SceneImage flip = findImage(images, "flip", reportDir);
    const SceneImage difference = findImage(images, "difference", reportDir);
    const std::string message = html::text(scene, "message");
    if (!expected.present() && !mine.present() && !flip.present() && !difference.present()) {
        messageShown = true;
        const std::string why = message.empty() ? "No images were written for this scene." : message;
        return "<div class=\"placeholder wide\">" + html::escape(why) + "</div>\n";
    }
    const SceneImage& base = expected.present() ? expected : mine;
    // A passed scene has nothing to find: it is shown at half the size (Enlarge still doubles it).
    const int full = compareScale(base), scale = html::text(scene, "status") == "passed" ? std::max(1, full / 2) : full;
    const int mapScale = std::max(1, scale / 2);
    std::string out = "<div class=\"figures\">\n";
    if (base.present()) out += compareWidget(expected, mine, scale, captions, id);
    if (!mine.present()) {  // the student's slot says why there is no image (the scene's message)
        messageShown = !message.empty();
        out += "<figure>" + std::string("<div class=\"placeholder why\" style=\"width:") +
               std::to_string(base.width > 0 ? mapScale * base.width : 256) + "px\">" +
               html::escape(message.empty() ? "not written" : message) + "</div><figcaption>" + captions.mine +
               "</figcaption></figure>\n";
    }
    const std::string noComparison = mine.present() ? "not written" : "no image to compare";
    out += "<div class=\"maps\">" +
           mapFigure(flip, mapScale, base, "FLIP error",
                     "perceived difference (Andersson et al. 2020): black none, yellow large", noComparison) +
           mapFigure(difference, mapScale, base, "Difference",
                     "per-pixel |difference|, amplified; red where a pixel is over the bound", noComparison) +
           "</div>\n";
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

std::string sceneBlock(const json& scene, const std::string& reportDir, const Captions& captions, IdMaker& ids,
                       const std::string& stageId) {
    const std::string name = html::text(scene, "name");
    const std::string message = html::text(scene, "message");
    const std::string id = ids.make(stageId + "-", name);
    std::string out = "<div class=\"scene\" id=\"" + id + "\">\n<div class=\"scene-head\">"
                      "<span class=\"scene-name\">" + html::escape(name) + "</span>" +
                      html::badge(html::text(scene, "status"));
    const auto maxScore = html::number(scene, "max_score");
    if (!maxScore || *maxScore > 0.0)  // a worked example's scenes carry no points: no "0 / 0"
        out += "<span class=\"score\">" +
               html::escape(html::formatScore(html::number(scene, "score"), maxScore)) + "</span>";
    out += "</div>\n";
    const std::string about = html::text(scene, "about"), setup = html::text(scene, "setup");
    const std::string file = html::text(scene, "scene_file");
    if (!about.empty()) out += "<p class=\"about\">" + html::escape(about) + "</p>\n";
    if (!setup.empty() || !file.empty())
        out += "<p class=\"setup\">" + (file.empty() ? "" : "<code>" + html::escape(file) + "</code> ") +
               html::escape(setup) + "</p>\n";
    // The starter code's stubs this scene reached (the checkerboard, or a C++ stub).
    std::string reached;
    for (const json& stub : html::array(scene, "not_implemented_reached"))
        if (stub.is_string()) reached += (reached.empty() ? "" : ", ") + stub.get<std::string>() + "()";
    if (!reached.empty())
        out += "<p class=\"setup\">Reached functions not yet implemented: <code>" + html::escape(reached) + "</code></p>\n";
    bool messageShown = false;
    const std::string images = figures(scene, reportDir, captions, "cmp-" + id, messageShown);
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
        const std::string inputs = html::checkInputsText(html::object(check, "inputs"));
        if (!inputs.empty()) out += "<div class=\"inputs\">Inputs: " + html::escape(inputs) + "</div>";
        const json& examples = html::array(check, "examples");
        if (!examples.empty()) {
            out += std::string("<details") + (status == "passed" ? "" : " open") + "><summary>" +
                   std::to_string(examples.size()) + (examples.size() == 1 ? " example" : " examples") +
                   "</summary><ul class=\"examples\">";
            for (const json& example : examples) {
                const std::string text = example.is_string()
                                             ? example.get<std::string>()
                                             : example.dump(-1, ' ', false, json::error_handler_t::replace);
                out += "<li><code>" + html::escape(text) + "</code></li>";
            }
            out += "</ul></details>";
        }
        out += "</td></tr>\n";
    }
    return out + "</tbody></table>\n";
}

std::string stageSection(const json& stage, const std::string& id, const std::string& reportDir, const Captions& captions,
                         IdMaker& ids) {
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
    if (!about.empty())
        out += "<p class=\"about\"><span class=\"label\">What this stage tests:</span> " + html::escape(about) + "</p>\n";
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
        for (const json& scene : scenes) out += sceneBlock(scene, reportDir, captions, ids, id);
        out += "<p class=\"legend\">Drag across an image to move the split between " + captions.expected +
               " (left) and " + captions.mine + " (right), or show either alone; Enlarge doubles the size. "
               "FLIP: black means no perceived difference, bright yellow a large one. "
               "Difference: per-pixel |difference|, amplified; red marks pixels over the bound. "
               "Click a map to open it at full size.</p>\n";
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
    std::string missing;
    if (results.contains("sandbox_missing") && results["sandbox_missing"].is_array())
        for (const json& layer : results["sandbox_missing"])
            if (layer.is_string()) missing += (missing.empty() ? "" : ", ") + layer.get<std::string>();
    meta("Isolation missing here", missing);
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

std::string htmlReportPage(const json& results, const std::string& reportDir) {
    const json& stages = html::array(results, "stages");
    IdMaker ids;
    std::vector<std::string> stageIds;
    for (const json& stage : stages) stageIds.push_back(ids.make("stage-", html::text(stage, "stage")));

    std::string body = header(results, stages) + "<main>\n";
    if (!stages.empty()) body += summaryTable(stages, stageIds);
    const Captions captions = captionsFor(html::text(results, "mode"));
    for (std::size_t i = 0; i < stages.size(); ++i)
        body += stageSection(stages[i], stageIds[i], reportDir, captions, ids);
    body += "</main>\n<footer>Written by voxlab grade. This folder is self-contained and works offline.</footer>\n";

    const std::string name = html::text(results, "name");
    return html::page((name.empty() ? std::string("Submission") : name) + " \u2013 voxlab report", body,
                      html::compareSliderScript);
}

void writeHtmlReport(const json& results, const std::string& reportDir) {
    writeFileAtomically((fs::path(reportDir) / "index.html").string(), htmlReportPage(results, reportDir));
}

}  // namespace voxlab
