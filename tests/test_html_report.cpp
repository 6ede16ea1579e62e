// The grader's HTML reports (html_report.h): every stage, scene and check of
// the results appears; every image the page shows is a file in the report
// folder; text from results is escaped; nothing points outside the folder;
// partial results do not crash; an unwritable folder is an error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "voxlab/error.h"
#include "voxlab/html_report.h"
#include "voxlab/image.h"

namespace {

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

std::string readText(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
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
             {"scenes", json::array({
                 {{"name", "bonsai_oblique"}, {"score", 1.6}, {"max_score", 2}, {"status", "failed"},
                  {"message", "SSIM 0.973 below 0.98"},
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

TEST(HtmlReport, EveryImageShownIsAFileInTheFolderAtTwiceItsSize) {
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
    // 32 x 24 images are shown at 64 x 48, pixels kept sharp.
    EXPECT_EQ(attributeValues(html, "width"), std::vector<std::string>(6, "64"));
    EXPECT_EQ(attributeValues(html, "height"), std::vector<std::string>(6, "48"));
    EXPECT_NE(html.find("image-rendering: pixelated"), std::string::npos);
}

TEST(HtmlReport, EscapesTextFromResults) {
    const fs::path dir = freshFolder("escaping");
    json results = fullResults(dir);
    results["name"] = "bob \"&\" <b>";
    voxlab::writeHtmlReport(results, dir.string());
    const std::string html = readText(dir / "index.html");
    EXPECT_EQ(html.find(hostile), std::string::npos);
    EXPECT_EQ(html.find("<script"), std::string::npos) << "the submission's page needs no script";
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

}  // namespace
