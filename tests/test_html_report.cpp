// The grader's HTML reports (html_report.h): every stage, scene and check of
// the results appears; every image the page shows is a file in the report
// folder; text from results is escaped; nothing points outside the folder;
// partial results do not crash; an unwritable folder is an error.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "voxlab/error.h"
#include "voxlab/grader.h"
#include "voxlab/html_report.h"
#include "voxlab/image.h"
#include "support/temp_dir.h"

namespace {

using voxlab::testing::readText;

using nlohmann::json;
namespace fs = std::filesystem;

const std::string hostile = "<script>alert(1)</script>";
const std::string hostileEscaped = "&lt;script&gt;alert(1)&lt;/script&gt;";

// A fresh folder of this test's own under the test temp folder.
fs::path freshFolder(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / ("voxlab_html_report_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// A small gradient image, so that its size can be checked on the page.
void writeTestPng(const fs::path& path, int width, int height) {
    voxlab::Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) image.set(x, y, {x / float(width), y / float(height), 0.5f, 1.0f});
    fs::create_directories(path.parent_path());
    voxlab::savePng(image, path.string());
}

// Decodes %XX escapes (the page percent-encodes paths in src and href).
std::string percentDecoded(const std::string& text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size()) {
            out += char(std::stoi(text.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += text[i];
        }
    }
    return out;
}

std::vector<std::string> attributeValues(const std::string& html, const std::string& attribute) {
    std::vector<std::string> values;
    const std::regex pattern("\\b" + attribute + "=\"([^\"]*)\"");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), pattern); it != std::sregex_iterator(); ++it)
        values.push_back((*it)[1]);
    return values;
}

// A graded submission with three stages: one with images and checks, one
// that did not compile, one whose scene errored before writing images. The
// four images of the first scene are written (one of them under a name with
// a space); the second scene names a FLIP image that was never written.
json fullResults(const fs::path& dir) {
    for (const char* kind : {"reference", "submission", "flip", "difference"})
        writeTestPng(dir / "mip" / (std::string("bonsai oblique.") + kind + ".png"), 32, 24);
    writeTestPng(dir / "mip" / "stent_front.reference.png", 32, 24);
    writeTestPng(dir / "mip" / "stent_front.submission.png", 32, 24);
    return json{
        {"submission", "/home/students/alice"}, {"name", "alice"}, {"graded_at", "2026-11-22T07:10:00Z"},
        {"mode", "grade"}, {"machine", "Mesa llvmpipe (LLVM 15.0.6, 256 bits), 2 threads"}, {"elapsed_s", 41.2},
        {"score", 12.5}, {"max_score", 30},
        {"stages", json::array({
            {{"stage", "mip"}, {"title", "Maximum intensity projection"}, {"score", 8.2}, {"max_score", 10},
             {"status", "failed"}, {"message", "1 of 2 scenes over the bound"}, {"elapsed_s", 3.1},
             {"about", "MIP of four datasets & a signed CT"},
             {"scenes", json::array({
                 {{"name", "bonsai_oblique"}, {"score", 1.6}, {"max_score", 2}, {"status", "failed"},
                  {"message", "SSIM 0.973 below 0.98"}, {"about", "the bonsai's <thin> branches"},
                  {"scene_file", "mip/scenes/bonsai_oblique.json"},
                  {"setup", "dataset: bonsai.nrrd; renderer: mip; size: [32, 24]"},
                  {"images", {{"reference", "mip/bonsai oblique.reference.png"},
                              {"submission", "mip/bonsai oblique.submission.png"},
                              {"flip", "mip/bonsai oblique.flip.png"},
                              {"difference", "mip/bonsai oblique.difference.png"}}},
                  {"metrics", {{"fraction_over", 0.012}, {"max_difference", 37}, {"ssim", 0.973}, {"ssim_min", 0.41},
                               {"flip_mean", 0.011}, {"flip_max", 0.62}, {"psnr", 31.2}}},
                  {"tolerance", {{"max_difference", 4}, {"max_fraction", 0.005}, {"min_ssim", 0.98},
                                 {"max_flip", 0.02}}}},
                 {{"name", "stent_front"}, {"score", 2}, {"max_score", 2}, {"status", "passed"},
                  {"images", {{"reference", "mip/stent_front.reference.png"},
                              {"submission", "mip/stent_front.submission.png"},
                              {"flip", "mip/stent_front.flip.png"}}},
                  {"metrics", {{"psnr", nullptr}}}}})},
             {"checks", json::array({
                 {{"name", "mip_random_rays"}, {"description", "maximum along random rays"}, {"score", 0},
                  {"max_score", 2}, {"status", "failed"}, {"message", "37 of 200 cases differ"},
                  {"inputs", {{"seed", "0x5EED000A"},
                              {"volume", {{"dims", {6, 7, 5}}, {"spacing", {1.3, 0.8, 1.1}}, {"extent", {7.8, 5.6, 5.5}},
                                          {"values", "data value = stored value x 65535 - 32768"}}},
                              {"units", "world units for points"}}},
                  {"examples", json::array({"ray (0,0,1): expected 0.8 got 0.7", hostile})}}})}},
            {{"stage", "phong"}, {"title", "Phong shading"}, {"score", 0}, {"max_score", 10},
             {"status", "compile_error"}, {"message", "phong/phong.glsl did not compile"},
             {"log", "phong/phong.glsl:14:9: error: 'normalise' : no matching overloaded function found\n"
                     "phong/phong.glsl:20:1: warning: unused variable"}},
            {{"stage", "iso"}, {"title", "Isosurface"}, {"score", 4.3}, {"max_score", 10}, {"status", "timeout"},
             {"message", hostile},
             {"scenes", json::array({{{"name", "bucky_iso"}, {"status", "error"}, {"message", "timed out after 60 s"},
                                      {"score", 0}, {"max_score", 2}}})}}})}};
}

TEST(HtmlReport, ShowsEveryStageSceneAndCheck) {
    const fs::path dir = freshFolder("full");
    voxlab::writeHtmlReport(fullResults(dir), dir.string());
    ASSERT_TRUE(fs::is_regular_file(dir / "index.html"));
    const std::string html = readText(dir / "index.html");
    for (const char* text : {"alice", "Maximum intensity projection", "Phong shading", "Isosurface", "bonsai_oblique",
                             "stent_front", "bucky_iso", "mip_random_rays", "12.5", "8.2 / 10", "timed out after 60 s",
                             "compile error", "not written"})
        EXPECT_NE(html.find(text), std::string::npos) << text;
    // The summary links to each stage's section.
    for (const char* stage : {"mip", "phong", "iso"}) {
        const std::string id = std::string("stage-") + stage;
        EXPECT_NE(html.find("href=\"#" + id + "\""), std::string::npos) << id;
        EXPECT_NE(html.find("id=\"" + id + "\""), std::string::npos) << id;
    }
}

TEST(HtmlReport, EveryImageShownIsAFileInTheFolderMagnifiedWithSharpPixels) {
    const fs::path dir = freshFolder("images");
    voxlab::writeHtmlReport(fullResults(dir), dir.string());
    const std::string html = readText(dir / "index.html");
    const std::vector<std::string> sources = attributeValues(html, "src");
    // Four images of the first scene and the two written of the second; the
    // FLIP image named but never written is a placeholder instead.
    EXPECT_EQ(sources.size(), 6u);
    for (const std::string& source : sources) {
        EXPECT_EQ(source.find_first_of(" \"'<>#?&"), std::string::npos) << source << " is not percent-encoded";
        EXPECT_FALSE(fs::path(percentDecoded(source)).is_absolute()) << source;
        EXPECT_TRUE(fs::is_regular_file(dir / percentDecoded(source))) << source;
    }
    // 32 x 24 images: the failed scene's comparison at 16 times (the largest
    // whole factor within 512 px), its maps at half that; the passed scene's
    // comparison at half size.
    EXPECT_EQ(attributeValues(html, "width"), (std::vector<std::string>{"512", "512", "256", "256", "256", "256"}));
    EXPECT_EQ(attributeValues(html, "height"), (std::vector<std::string>{"384", "384", "192", "192", "192", "192"}));
    EXPECT_NE(html.find("image-rendering: pixelated"), std::string::npos);
}

// Each comparison stacks the student's image over the expected one, split
// by a slider, with buttons for either alone and for a larger view; a
// self-check calls them "Expected" and "Yours".
TEST(HtmlReport, ComparesTheImagesWithASliderAndButtons) {
    const fs::path dir = freshFolder("compare");
    json results = fullResults(dir);
    voxlab::writeHtmlReport(results, dir.string());
    std::string html = readText(dir / "index.html");
    const std::size_t compare = html.find("<div class=\"compare\">");
    ASSERT_NE(compare, std::string::npos);
    const std::size_t under = html.find("class=\"under\" src=\"mip/bonsai%20oblique.reference.png\"", compare);
    const std::size_t over = html.find("class=\"over\" src=\"mip/bonsai%20oblique.submission.png\"", compare);
    EXPECT_LT(under, over);
    EXPECT_NE(html.find("type=\"range\" class=\"slider\"", over), std::string::npos);
    for (const char* control : {"type=\"radio\" class=\"v-split\"", "type=\"radio\" class=\"v-expected\"",
                                "type=\"radio\" class=\"v-mine\"", "type=\"checkbox\" class=\"v-zoom\"",
                                ">Enlarge</label>", ">Reference</label>", ">Submission</label>"})
        EXPECT_NE(html.find(control, compare), std::string::npos) << control;
    // Radio groups are per scene: two scenes with images, two groups.
    std::set<std::string> groups;
    const std::regex radio("type=\"radio\" class=\"v-[a-z]+\" name=\"([^\"]+)\"");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), radio); it != std::sregex_iterator(); ++it)
        groups.insert((*it)[1]);
    EXPECT_EQ(groups.size(), 2u);

    results["mode"] = "check";
    voxlab::writeHtmlReport(results, dir.string());
    html = readText(dir / "index.html");
    EXPECT_NE(html.find(">Expected</label>"), std::string::npos);
    EXPECT_NE(html.find(">Yours</label>"), std::string::npos);
    EXPECT_EQ(html.find(">Submission</label>"), std::string::npos);
}

// The stage's and the scene's "about", the scene file and its settings.
TEST(HtmlReport, ShowsWhatEachStageAndSceneIsAbout) {
    const fs::path dir = freshFolder("about");
    voxlab::writeHtmlReport(fullResults(dir), dir.string());
    const std::string html = readText(dir / "index.html");
    const std::size_t scene = html.find("id=\"stage-mip-bonsai_oblique\"");
    ASSERT_NE(scene, std::string::npos);
    EXPECT_LT(html.find("MIP of four datasets &amp; a signed CT"), scene);
    const std::size_t images = html.find("<div class=\"compare\">", scene);
    for (const char* text : {"the bonsai&#39;s &lt;thin&gt; branches", "mip/scenes/bonsai_oblique.json",
                             "dataset: bonsai.nrrd; renderer: mip; size: [32, 24]"}) {
        const std::size_t at = html.find(text, scene);
        EXPECT_LT(at, images) << text << " is not shown with its scene, before its images";
    }
}

// A failing check says how to rebuild its inputs: seed, volume, units.
TEST(HtmlReport, SaysHowToReproduceAFailingCheck) {
    const fs::path dir = freshFolder("inputs");
    voxlab::writeHtmlReport(fullResults(dir), dir.string());
    const std::string html = readText(dir / "index.html");
    const std::size_t check = html.find(">mip_random_rays<");
    ASSERT_NE(check, std::string::npos);
    for (const char* text : {"seed 0x5EED000A", "random volume of 6 x 7 x 5 voxels", "spacing 1.3 x 0.8 x 1.1",
                             "(box 7.8 x 5.6 x 5.5)", "data value = stored value x 65535 - 32768",
                             "units: world units for points"})
        EXPECT_NE(html.find(text, check), std::string::npos) << text;
}

TEST(HtmlReport, EscapesTextFromResults) {
    const fs::path dir = freshFolder("escaping");
    json results = fullResults(dir);
    results["name"] = "bob \"&\" <b>";
    voxlab::writeHtmlReport(results, dir.string());
    const std::string html = readText(dir / "index.html");
    EXPECT_EQ(html.find(hostile), std::string::npos);
    // One script, inline: the comparisons' sliders.
    const std::size_t script = html.find("<script");
    ASSERT_NE(script, std::string::npos);
    EXPECT_EQ(html.find("<script", script + 1), std::string::npos);
    EXPECT_EQ(html.compare(script, 9, "<script>\n"), 0) << "the script is inline";
    EXPECT_NE(html.find(hostileEscaped), std::string::npos);
    EXPECT_EQ(html.find("<b>"), std::string::npos);
    EXPECT_NE(html.find("bob &quot;&amp;&quot; &lt;b&gt;"), std::string::npos);
}

TEST(HtmlReport, PointsNowhereOutsideTheFolder) {
    const fs::path dir = freshFolder("offline");
    voxlab::writeHtmlReport(fullResults(dir), dir.string());
    const std::string html = readText(dir / "index.html");
    for (const char* external : {"http://", "https://", "//", "url(", "@import", "file:"})
        EXPECT_EQ(html.find(external), std::string::npos) << external;
    for (const std::string& link : attributeValues(html, "href"))
        EXPECT_TRUE(link[0] == '#' || fs::is_regular_file(dir / percentDecoded(link))) << link;
}

TEST(HtmlReport, ShowsTheCompilerLogOfAStageThatDidNotCompile) {
    const fs::path dir = freshFolder("log");
    voxlab::writeHtmlReport(fullResults(dir), dir.string());
    const std::string html = readText(dir / "index.html");
    const std::size_t section = html.find("id=\"stage-phong\"");
    const std::size_t nextSection = html.find("id=\"stage-iso\"");
    ASSERT_NE(section, std::string::npos);
    const std::size_t log = html.find("<pre", section);
    ASSERT_LT(log, nextSection);
    const std::size_t line = html.find(
        "phong/phong.glsl:14:9: error: &#39;normalise&#39; : no matching overloaded function found", log);
    EXPECT_LT(line, html.find("</pre>", log));
    EXPECT_NE(html.find("phong/phong.glsl:20:1: warning: unused variable", log), std::string::npos);
}

// The metric tiles carry their verdict: SSIM 0.973 < 0.98 and 1.2 % > 0.5 %
// of pixels over the threshold fail; FLIP 0.011 <= 0.02 passes; PSNR is
// shown only (and infinite when given as null).
TEST(HtmlReport, MarksEachMetricAgainstItsBound) {
    const fs::path dir = freshFolder("metrics");
    voxlab::writeHtmlReport(fullResults(dir), dir.string());
    const std::string html = readText(dir / "index.html");
    // The class of the metric tile whose label starts with `label`.
    const auto tileClass = [&html](const std::string& label) {
        const std::size_t at = html.find("<div class=\"m-label\">" + label);
        if (at == std::string::npos) return std::string("(no tile)");
        const std::size_t tile = html.rfind("<div class=\"metric ", at);
        return html.substr(tile + 19, html.find('"', tile + 19) - tile - 19);
    };
    EXPECT_EQ(tileClass("SSIM, mean"), "bad");
    EXPECT_EQ(tileClass("Pixels off by &gt; 4/255"), "bad");
    EXPECT_EQ(tileClass("FLIP, mean"), "ok");
    EXPECT_EQ(tileClass("PSNR"), "shown");
    EXPECT_NE(html.find("\u2265 0.98"), std::string::npos);
    EXPECT_NE(html.find("\u221e dB"), std::string::npos);
}

TEST(HtmlReport, WorksWithOnlyTheRequiredFields) {
    const fs::path dir = freshFolder("minimal");
    const json minimal = {{"stages", json::array({
        {{"stage", "composite"}, {"score", 0}, {"max_score", 10}, {"status", "not_implemented"},
         {"scenes", json::array({{{"name", "bonsai_front"}, {"status", "error"}}})},
         {"checks", json::array({{{"name", "over_operator"}, {"status", "failed"}}})}}})}};
    ASSERT_NO_THROW(voxlab::writeHtmlReport(minimal, dir.string()));
    const std::string html = readText(dir / "index.html");
    for (const char* text : {"composite", "not implemented", "bonsai_front", "over_operator", "0 / 10"})
        EXPECT_NE(html.find(text), std::string::npos) << text;

    // Nothing at all, and fields of the wrong type, are shown as missing.
    EXPECT_NO_THROW(voxlab::writeHtmlReport(json::object(), dir.string()));
    EXPECT_NO_THROW(voxlab::writeHtmlReport(json::array(), dir.string()));
    const json wrongTypes = {{"name", 5}, {"score", "lots"}, {"stages", json::array({
        nullptr, {{"stage", 3}, {"scenes", "none"}, {"checks", json::array({1, "x"})}, {"log", json::array()}},
        {{"scenes", json::array({{{"images", "none"}, {"metrics", {{"ssim", "high"}, {"psnr", true}}}}})}}})}};
    EXPECT_NO_THROW(voxlab::writeHtmlReport(wrongTypes, dir.string()));
    EXPECT_NO_THROW(voxlab::writeClassHtmlReport(wrongTypes, dir.string()));
    EXPECT_NO_THROW(voxlab::writeClassHtmlReport(json::array({wrongTypes, 7}), dir.string()));
}

TEST(HtmlReport, AFolderThatCannotBeWrittenIsAnError) {
    const fs::path dir = freshFolder("unwritable");
    // Under a regular file nothing can be created, whoever runs the test.
    std::ofstream(dir / "a_file") << "not a folder";
    const std::string inside = (dir / "a_file" / "report").string();
    EXPECT_THROW(voxlab::writeHtmlReport(fullResults(dir), inside), voxlab::Error);
    EXPECT_THROW(voxlab::writeClassHtmlReport(json::array(), inside), voxlab::Error);
    EXPECT_THROW(voxlab::writeHtmlReport(json::object(), (dir / "missing").string()), voxlab::Error);
}

TEST(ClassHtmlReport, ListsEverySubmissionWithLinksToItsReport) {
    const fs::path dir = freshFolder("class");
    const json alice = fullResults(dir / "alice");
    json bob = {{"name", "bob & co"}, {"status", "error"}, {"message", hostile},
                {"stages", json::array({{{"stage", "mip"}, {"score", 10}, {"max_score", 10}, {"status", "passed"}}})}};
    voxlab::writeHtmlReport(alice, (dir / "alice").string());
    fs::create_directories(dir / "bob & co");
    voxlab::writeHtmlReport(bob, (dir / "bob & co").string());
    voxlab::writeClassHtmlReport({{"title", "CS 4410 volume rendering"}, {"submissions", json::array({alice, bob})}},
                                 dir.string());

    const std::string html = readText(dir / "index.html");
    std::vector<std::string> links = attributeValues(html, "href");
    ASSERT_EQ(links.size(), 2u);
    for (const std::string& link : links) EXPECT_TRUE(fs::is_regular_file(dir / percentDecoded(link))) << link;
    EXPECT_EQ(percentDecoded(links[1]), "bob & co/index.html");
    // A column per stage (bob has only mip), with totals and scores.
    for (const char* text : {"CS 4410 volume rendering", ">mip<", ">phong<", ">iso<", "12.5 / 30", "8.2", "10 / 10",
                             "bob &amp; co", hostileEscaped.c_str()})
        EXPECT_NE(html.find(text), std::string::npos) << text;
    EXPECT_EQ(html.find(hostile), std::string::npos);
    for (const char* external : {"http://", "https://", "url(", "@import"})
        EXPECT_EQ(html.find(external), std::string::npos) << external;
    // Rows sort from their cells' data-sort keys.
    EXPECT_NE(html.find("data-sort=\"12.5\""), std::string::npos);
    EXPECT_NE(html.find("addEventListener('click'"), std::string::npos);
}

// The page's text without tags and attribute values (a title= tooltip
// does not count as shown).
std::string visibleText(const std::string& html) {
    return std::regex_replace(html, std::regex("<[^>]*>"), " ");
}

// A class in which bob's mip did not compile and carol has not started.
json classGradebook() {
    const auto stage = [](const char* name, double score, double max, const char* status, const char* message) {
        return json{{"stage", name}, {"score", score}, {"max_score", max}, {"status", status}, {"message", message}};
    };
    const json example = stage("slicer", 0, 0, "example", "every scene and check within its tolerance");
    return {{"submissions", json::array({
        {{"name", "alice"}, {"stages", json::array({example, stage("mip", 10, 10, "passed", ""),
                                                    stage("iso", 4, 10, "failed", "2 of 5 items outside tolerance")})}},
        {{"name", "bob_with_a_long_name"},
         {"stages", json::array({example, stage("mip", 0, 10, "compile_error",
                                                "mip/mip.glsl:21:2: error: syntax error, unexpected BASIC_TYPE_TOK"),
                                 stage("iso", 0, 10, "not_implemented", "iso_hit is not yet implemented")})}},
        {{"name", "carol"}, {"stages", json::array({example, stage("mip", 0, 10, "not_implemented", ""),
                                                    stage("iso", 0, 10, "not_implemented", "")})}}})}};
}

// voxlab grade --batch writes similarity.html beside the class page, which
// links it (and says so when the comparison was off or failed).
TEST(ClassHtmlReport, LinksTheSimilarityReport) {
    json gradebook = classGradebook();
    gradebook["similarity"] = {{"page", "similarity.html"}, {"summary", "2 pair(s) listed"}};
    const std::string html = voxlab::classHtmlReportPage(gradebook);
    const std::vector<std::string> links = attributeValues(html, "href");
    EXPECT_NE(std::find(links.begin(), links.end(), "similarity.html"), links.end()) << html;
    EXPECT_NE(visibleText(html).find("2 pair(s) listed"), std::string::npos);
    gradebook["similarity"] = {{"off", true}};
    EXPECT_NE(visibleText(voxlab::classHtmlReportPage(gradebook)).find("not compared"), std::string::npos);
    gradebook["similarity"] = {{"error", "<b>disk full</b>"}};
    const std::string failed = voxlab::classHtmlReportPage(gradebook);
    EXPECT_NE(failed.find("&lt;b&gt;disk full"), std::string::npos);
    const std::vector<std::string> none = attributeValues(failed, "href");
    EXPECT_EQ(std::find(none.begin(), none.end(), "similarity.html"), none.end()) << "a link to a page never written";
}

TEST(ClassHtmlReport, ACompileErrorIsVisibleTextInItsRow) {
    const fs::path dir = freshFolder("class_compile_error");
    voxlab::writeClassHtmlReport(classGradebook(), dir.string());
    const std::string html = readText(dir / "index.html");
    const std::size_t row = html.find("<tr><td class=\"who\" data-sort=\"bob_with_a_long_name\"");
    ASSERT_NE(row, std::string::npos);
    const std::string text = visibleText(html.substr(row, html.find("</tr>", row) - row));
    // In the name's cell, with its message, before the unfinished stage...
    const std::size_t error = text.find("compile error");
    EXPECT_NE(error, std::string::npos) << text;
    EXPECT_NE(text.find("mip/mip.glsl:21:2: error: syntax error", error), std::string::npos) << text;
    EXPECT_LT(error, text.find("not implemented")) << text;
    // ... and under the stage's score.
    EXPECT_NE(html.find("<div class=\"note\">compile error</div>", row), std::string::npos);
}

// Fifteen stages with long names: each heading runs upwards (its width
// does not grow with the name) and long submission names may break at
// underscores. Whether the page then fits 1280 px is a browser's to say:
// the page is left in the test's temp folder (voxlab_html_report_class_wide)
// for a look.
TEST(ClassHtmlReport, FifteenStagesWithLongNamesRunUpwards) {
    const fs::path dir = freshFolder("class_wide");
    json submissions = json::array();
    for (const char* name : {"a_student_with_a_very_long_name_indeed", "bob", "carol"}) {
        json stages = json::array();
        for (int i = 0; i < 15; ++i)
            stages.push_back({{"stage", "a_rather_long_stage_name_" + std::to_string(i)}, {"score", 7.25},
                              {"max_score", 10}, {"status", i == 3 ? "compile_error" : "failed"},
                              {"message", i == 3 ? "stage_3/stage.glsl:12:4: error: 'sample_volume' : no matching "
                                                   "overloaded function found" : "2 of 5 items outside tolerance"}});
        submissions.push_back({{"name", name}, {"stages", stages}});
    }
    voxlab::writeClassHtmlReport(submissions, dir.string());
    const std::string html = readText(dir / "index.html");
    for (int i = 0; i < 15; ++i) {
        const std::string heading = "<span class=\"up\">a_rather_long_stage_name_" + std::to_string(i) + "</span>";
        EXPECT_NE(html.find(heading), std::string::npos) << heading;
    }
    EXPECT_NE(html.find("writing-mode: vertical-rl"), std::string::npos);
    EXPECT_NE(html.find(">a_<wbr>student_<wbr>with_<wbr>a_<wbr>very_<wbr>long_<wbr>name_<wbr>indeed</a>"),
              std::string::npos);
}

// A stage worth 0 points in every submission (the worked example) has no
// column, and no "x / 0" appears on either page.
TEST(ClassHtmlReport, AWorkedExampleHasNoOutOfZeroColumn) {
    const fs::path dir = freshFolder("class_example");
    const json gradebook = classGradebook();
    voxlab::writeClassHtmlReport(gradebook, dir.string());
    const std::string html = readText(dir / "index.html");
    EXPECT_EQ(html.find(">slicer<"), std::string::npos);
    EXPECT_EQ(std::regex_search(html, std::regex("/ 0(?![.0-9])")), false);
    EXPECT_NE(html.find(">mip<"), std::string::npos);
    EXPECT_NE(html.find("/ 10"), std::string::npos);

    voxlab::writeHtmlReport(gradebook["submissions"][0], dir.string());
    const std::string report = readText(dir / "index.html");
    EXPECT_NE(report.find("slicer"), std::string::npos);
    EXPECT_EQ(std::regex_search(report, std::regex("/ 0(?![.0-9])")), false);
    EXPECT_NE(report.find("not graded"), std::string::npos);
}

// Problems worst first, whatever order the stages were graded in: compile
// error, crashed, timeout, error, failed, not implemented.
TEST(ClassHtmlReport, ProblemsComeWorstFirst) {
    const auto stage = [](const char* name, const char* status) {
        return json{{"stage", name}, {"status", status}, {"score", 0}, {"max_score", 10},
                    {"message", "m " + std::string(name)}};
    };
    const json results = {{"name", "dave"},
                          {"stages", json::array({stage("a", "not_implemented"), stage("b", "failed"),
                                                  stage("c", "passed"), stage("d", "error"), stage("e", "timeout"),
                                                  stage("f", "crashed"), stage("g", "compile_error"),
                                                  stage("h", "example"), stage("i", "not_implemented")})}};
    std::vector<std::string> order;
    for (const voxlab::StageProblem& p : voxlab::stageProblems(results)) order.push_back(p.stage + ":" + p.status);
    EXPECT_EQ(order, (std::vector<std::string>{"g:compile_error", "f:crashed", "e:timeout", "d:error", "b:failed",
                                               "a:not_implemented", "i:not_implemented"}));
    EXPECT_EQ(voxlab::problemsSummary(results),
              "g: compile_error (m g); f: crashed (m f); e: timeout (m e); d: error (m d); b: failed; "
              "a: not_implemented; i: not_implemented");

    const fs::path dir = freshFolder("class_order");
    voxlab::writeClassHtmlReport(json::array({results}), dir.string());
    const std::string text = visibleText(readText(dir / "index.html"));
    std::size_t at = 0;
    for (const char* label : {"compile error", "crashed", "timeout", "error", "failed", "not implemented"}) {
        const std::size_t next = text.find(label, at);
        ASSERT_NE(next, std::string::npos) << label << " missing or out of order";
        at = next;
    }
}

// ---------------------------------------------------------------------------
// results.json (grader.h: gradescopeResults)

// Noise does not compress, so each image's size is predictable.
void writeNoisePng(const fs::path& path, int width, int height, unsigned seed) {
    voxlab::Image image(width, height);
    for (float& v : image.rgba) {
        seed = seed * 1664525u + 1013904223u;
        v = float(seed >> 24) / 255.0f;
    }
    fs::create_directories(path.parent_path());
    voxlab::savePng(image, path.string());
}

json failedScene(const std::string& stage, const std::string& name) {
    const std::string base = stage + "/" + name;
    return {{"name", name}, {"status", "failed"}, {"score", 0}, {"max_score", 1}, {"message", "SSIM 0.5 < 0.98"},
            {"images", {{"reference", base + ".reference.png"}, {"submission", base + ".submission.png"},
                        {"flip", base + ".flip.png"}, {"difference", base + ".difference.png"}}}};
}

void writeSceneImages(const fs::path& dir, const std::string& stage, const std::string& name, int w, int h) {
    unsigned seed = unsigned(std::hash<std::string>()(stage + name));
    for (const char* kind : {"reference", "submission", "flip", "difference"})
        writeNoisePng(dir / stage / (name + "." + kind + ".png"), w, h, seed++);
}

// The base64 text of each src="data:image/png;base64,..." (found by hand:
// std::regex recurses per character and overflows the stack on long ones).
std::vector<std::string> dataUris(const std::string& output) {
    std::vector<std::string> uris;
    const std::string prefix = "src=\"data:image/png;base64,";
    for (std::size_t at = output.find(prefix); at != std::string::npos; at = output.find(prefix, at)) {
        at += prefix.size();
        const std::size_t end = output.find('"', at);
        if (end == std::string::npos) break;
        uris.push_back(output.substr(at, end - at));
    }
    return uris;
}

std::string decodeBase64(const std::string& text) {
    std::string out;
    int bits = 0, value = 0;
    for (char c : text) {
        const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const char* at = std::strchr(digits, c);
        if (c == '=' || !at) break;
        value = value << 6 | int(at - digits), bits += 6;
        if (bits >= 8) out += char((value >> (bits - 8)) & 255), bits -= 8;
    }
    return out;
}

// A PNG's width and height from its header (IHDR), or -1, -1.
std::pair<int, int> pngSize(const std::string& png) {
    if (png.size() < 24 || png.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || png.compare(12, 4, "IHDR") != 0)
        return {-1, -1};
    const auto word = [&](std::size_t at) {
        return int(std::uint8_t(png[at])) << 24 | int(std::uint8_t(png[at + 1])) << 16 |
               int(std::uint8_t(png[at + 2])) << 8 | int(std::uint8_t(png[at + 3]));
    };
    return {word(16), word(20)};
}

const json* findTest(const json& results, const std::string& name) {
    for (const json& t : results["tests"])
        if (t["name"] == name) return &t;
    return nullptr;
}

// A failed scene shows the expected image, the student's and the
// difference as PNGs in HTML output, at most 256 px on a side (a 600 x 300
// render is shrunk to 200 x 100); a passed one, and any results written
// without the report's folder, stay text.
TEST(GradescopeResults, AFailedSceneShowsItsImagesAsPngs) {
    const fs::path dir = freshFolder("results_images");
    writeSceneImages(dir, "mip", "small", 128, 128);
    writeSceneImages(dir, "mip", "wide", 600, 300);
    json passed = failedScene("mip", "small");
    passed["name"] = "fine", passed["status"] = "passed", passed["score"] = 1;
    const json report = {{"score", 1}, {"max_score", 3}, {"stages", json::array({
        {{"stage", "mip"}, {"title", "MIP"}, {"status", "failed"}, {"score", 1}, {"max_score", 3},
         {"scenes", json::array({failedScene("mip", "small"), failedScene("mip", "wide"), passed})}}})}};

    const json results = voxlab::gradescopeResults(report, dir.string());
    const std::pair<std::string, std::pair<int, int>> expected[] = {{"MIP: small", {128, 128}},
                                                                     {"MIP: wide", {200, 100}}};
    for (const auto& [name, size] : expected) {
        const json* test = findTest(results, name);
        ASSERT_NE(test, nullptr) << name;
        EXPECT_EQ(test->value("output_format", ""), "html") << name;
        const std::string output = (*test)["output"];
        EXPECT_NE(output.find("SSIM 0.5 &lt; 0.98"), std::string::npos) << "the message is escaped HTML";
        const std::vector<std::string> uris = dataUris(output);
        ASSERT_EQ(uris.size(), 3u) << name;
        for (const std::string& uri : uris) EXPECT_EQ(pngSize(decodeBase64(uri)), size) << name;
    }
    EXPECT_FALSE(findTest(results, "MIP: fine")->contains("output_format"));
    EXPECT_TRUE(dataUris(findTest(results, "MIP: fine")->value("output", "")).empty());
    for (const json& t : voxlab::gradescopeResults(report)["tests"]) {
        EXPECT_FALSE(t.contains("output_format")) << t["name"];
        EXPECT_TRUE(dataUris(t.value("output", "")).empty()) << t["name"];
    }
}

// The images of one results.json stay within kResultsImageBudget: noise
// images of 128 px take about 200 KB a scene, so five of six fit. The
// first failed scene of every stage comes before the others.
TEST(GradescopeResults, ImagesStayWithinTheBudgetFirstScenesFirst) {
    const fs::path dir = freshFolder("results_budget");
    json first = json::array(), second = json::array();
    for (int i = 1; i <= 4; ++i) {
        writeSceneImages(dir, "a", "a" + std::to_string(i), 128, 128);
        first.push_back(failedScene("a", "a" + std::to_string(i)));
    }
    for (int i = 1; i <= 2; ++i) {
        writeSceneImages(dir, "b", "b" + std::to_string(i), 128, 128);
        second.push_back(failedScene("b", "b" + std::to_string(i)));
    }
    const json report = {{"stages", json::array({
        {{"stage", "a"}, {"title", "A"}, {"status", "failed"}, {"score", 0}, {"max_score", 4}, {"scenes", first}},
        {{"stage", "b"}, {"title", "B"}, {"status", "failed"}, {"score", 0}, {"max_score", 2}, {"scenes", second}}})}};
    const json results = voxlab::gradescopeResults(report, dir.string());
    std::size_t total = 0;
    int withImages = 0, leftOut = 0;
    for (const json& t : results["tests"]) {
        for (const std::string& uri : dataUris(t.value("output", "")))
            total += uri.size() + 22;  // and "data:image/png;base64,"
        const bool images = !dataUris(t.value("output", "")).empty();
        withImages += images;
        leftOut += t.value("output", "").find("Images left out") != std::string::npos;
    }
    EXPECT_LE(total, voxlab::kResultsImageBudget);
    EXPECT_GE(withImages, 2);
    EXPECT_GE(leftOut, 1) << "six scenes of noise should not all fit";
    EXPECT_EQ(withImages + leftOut, 6);
    EXPECT_FALSE(dataUris(findTest(results, "B: b1")->value("output", "")).empty()) << "b1 is its stage's first";
    EXPECT_TRUE(dataUris(findTest(results, "B: b2")->value("output", "")).empty()) << "b2 comes last";
}

}  // namespace
