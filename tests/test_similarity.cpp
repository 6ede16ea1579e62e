// The similarity report of `voxlab grade --batch` (similarity.h), on a corpus
// of real stage code (tests/similarity/):
//  - reference: the reference solutions of sampling, composite, texslice3d
//    (C++) and mip, copied from reference/;
//  - copy_renamed: disguised copies of all four (names changed, comments
//    and layout rewritten, braces added, independent statements and whole
//    functions reordered);
//  - independent_a, independent_b: the same stages written independently of
//    the reference and of each other (loops over corners against explicit
//    lerps, transmittance against accumulated opacity, while against for,
//    an edge table and a walk against a pseudo-angle sort, ...).
// The starter code is the project's assignments/.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <unistd.h>
#include <vector>

#include "support/run_command.h"
#include "voxlab/error.h"
#include "voxlab/similarity.h"
#include "support/temp_dir.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = VOXLAB_SOURCE_DIR;
const fs::path kCorpus = kSource / "tests" / "similarity";
const std::string kStarter = (kSource / "assignments").string();

const std::vector<SimilarityStage> kStages = {{"sampling", {"sampling.glsl"}},
                                              {"composite", {"composite.glsl"}},
                                              {"texslice3d", {"proxy_geometry.cpp"}},
                                              {"mip", {"mip.glsl"}}};

const fs::path kScratch = fs::temp_directory_path() / ("voxlab_similarity_" + std::to_string(::getpid()));

fs::path scratch(const std::string& name) {
    const fs::path p = kScratch / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

struct RemoveScratch : ::testing::Environment {
    void TearDown() override { fs::remove_all(kScratch); }
};
const auto* const kRemoveScratch = ::testing::AddGlobalTestEnvironment(new RemoveScratch);

void writeText(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

// The corpus as a class: the reference's stage files copied into a
// submission folder of their own, the others as they are.
std::vector<SimilaritySubmission> corpus() {
    const fs::path ref = scratch("reference");
    for (const SimilarityStage& s : kStages)
        for (const std::string& f : s.files) {
            fs::create_directories(ref / s.stage);
            fs::copy_file(kSource / "reference" / s.stage / f, ref / s.stage / f);
        }
    return {{"reference", ref.string()},
            {"copy_renamed", (kCorpus / "copy_renamed").string()},
            {"independent_a", (kCorpus / "independent_a").string()},
            {"independent_b", (kCorpus / "independent_b").string()}};
}

const SimilarPair* findPair(const SimilarityReport& r, const std::string& stage, const std::string& a,
                            const std::string& b) {
    for (const SimilarPair& p : r.pairs)
        if (p.stage == stage && ((r.names[p.a] == a && r.names[p.b] == b) || (r.names[p.a] == b && r.names[p.b] == a)))
            return &p;
    return nullptr;
}

// Every pair that shares anything, whatever its score.
SimilarityOptions everything() {
    SimilarityOptions o;
    o.threshold = 1e-9;
    o.minMatchedTokens = 0;
    return o;
}

// ---- tokens -----------------------------------------------------------------

std::string joined(const std::vector<SourceToken>& tokens) {
    std::string s;
    for (const SourceToken& t : tokens) s += t.text + " ";
    return s;
}

TEST(SimilarityTokens, NamesCommentsLayoutAndBracesAreSetAside) {
    const std::string a = "float f(vec3 p) { float best = 0.0; // comment\n return max(best, p.x); }";
    const std::string b = "/* header */\nfloat   other_name ( vec3 q )\n{\n    float m = 0.;\n"
                          "    return max( m, q.x );  /* done */\n}\n";
    EXPECT_EQ(joined(tokenizeSource(a)), joined(tokenizeSource(b)));
    EXPECT_EQ(joined(tokenizeSource(a)), "float id ( vec3 id ) float id = 0 ; return max ( id , id . x ) ; ");
}

TEST(SimilarityTokens, BuiltinsAreKeptWhereCalledAndAreNamesElsewhere) {
    EXPECT_EQ(joined(tokenizeSource("double length = glm::length(v); float step = max (a, b);")),
              joined(tokenizeSource("double len = glm::length(v); float s = max(a, b);")));
    EXPECT_EQ(joined(tokenizeSource("n = points.size(); std::sort(p.begin(), p.end());")),
              "id = id . size ( ) ; std :: sort ( id . begin ( ) , id . end ( ) ) ; ");
    EXPECT_NE(joined(tokenizeSource("x = max(a, b);")), joined(tokenizeSource("x = min(a, b);")));
}

TEST(SimilarityTokens, NumbersAreKeptByValueAndPreprocessorLinesDropped) {
    EXPECT_EQ(joined(tokenizeSource("#include \"x.glsl\"\n#define A \\\n  1\nx = 1.0f + 1. + 1e0 + 0x1;")),
              "id = 1 + 1 + 1 + 1 ; ");
    EXPECT_NE(joined(tokenizeSource("x = 0.5;")), joined(tokenizeSource("x = 0.25;")));
    EXPECT_EQ(joined(tokenizeSource("a.xyz b.rgb c.t_entry")), "id . xyz id . rgb id . id ");
}

TEST(SimilarityTokens, LinesAreCounted) {
    const std::vector<SourceToken> t = tokenizeSource("/* a\n b */ x\n\n// c\ny \"s\ntr\" z");
    ASSERT_EQ(t.size(), 5u);
    EXPECT_EQ(t[0].line, 2);
    EXPECT_EQ(t[1].line, 5);
    EXPECT_EQ(t[2].text, "\"str\"");  // an unterminated string ends at its line
    EXPECT_EQ(t[3].line, 6);
}

TEST(SimilarityTokens, AnyBytesAreSafe) {
    EXPECT_TRUE(tokenizeSource("").empty());
    EXPECT_TRUE(tokenizeSource("/* never closed\n x = 1;").empty());
    EXPECT_EQ(tokenizeSource("x /").size(), 2u);
    EXPECT_EQ(tokenizeSource("\"never closed").size(), 1u);
    EXPECT_EQ(tokenizeSource("1e+").size(), 1u);
    std::string bytes;
    for (int i = 0; i < 256; ++i) bytes += char(i);
    EXPECT_NO_THROW(tokenizeSource(bytes + bytes));
    EXPECT_NO_THROW(tokenizeSource("\\"));
    EXPECT_NO_THROW(tokenizeSource("#"));
    EXPECT_NO_THROW(tokenizeSource("x = 0x;"));
}

// ---- the corpus ---------------------------------------------------------------

// The measurement behind the defaults: every pair's score and matching
// tokens, printed (run this test alone to see the table).
TEST(SimilarityMeasurement, CopiesScoreHighAndIndependentSolutionsLow) {
    const SimilarityReport r = findSimilarCode(corpus(), kStages, kStarter, everything());
    std::printf("%-11s %-14s %-14s %6s %7s %7s\n", "stage", "a", "b", "score", "tokA", "tokB");
    double lowestCopy = 1.0, highestOther = 0.0;
    for (const SimilarPair& p : r.pairs) {
        std::printf("%-11s %-14s %-14s %6.3f %7d %7d\n", p.stage.c_str(), r.names[p.a].c_str(),
                    r.names[p.b].c_str(), p.score, p.matchedTokensA, p.matchedTokensB);
        const bool copy = r.names[p.a] == "reference" && r.names[p.b] == "copy_renamed";
        if (copy) lowestCopy = std::min(lowestCopy, p.score);
        else highestOther = std::max(highestOther, p.score);
    }
    std::printf("lowest copy score %.3f, highest other score %.3f\n", lowestCopy, highestOther);
    for (const SimilarityStage& s : kStages) EXPECT_TRUE(findPair(r, s.stage, "reference", "copy_renamed")) << s.stage;
    EXPECT_GE(lowestCopy, 0.75);
    EXPECT_GT(lowestCopy, SimilarityOptions().threshold);
    EXPECT_LT(highestOther, SimilarityOptions().threshold);
}

TEST(Similarity, ADisguisedCopyIsFlaggedWithItsMatchingLines) {
    const SimilarityReport r = findSimilarCode(corpus(), kStages, kStarter, SimilarityOptions());
    for (const SimilarityStage& s : kStages) {  // mip too: 5 lines, but copied whole
        const std::string& stage = s.stage;
        const SimilarPair* p = findPair(r, stage, "reference", "copy_renamed");
        ASSERT_TRUE(p) << stage;
        EXPECT_GE(p->score, 0.75) << stage;
        ASSERT_FALSE(p->regions.empty()) << stage;
        for (const MatchedRegion& m : p->regions) {
            EXPECT_LE(m.firstA, m.lastA);
            EXPECT_LE(m.firstB, m.lastB);
            EXPECT_GE(m.tokens, SimilarityOptions().kgram);
        }
    }
    // The trilinear body of the copy (its lines 17-39) is matched, not only its signature.
    const SimilarPair* p = findPair(r, "sampling", "reference", "copy_renamed");
    const bool copyIsB = r.names[p->b] == "copy_renamed";
    int matchedLines = 0;
    for (int line = 17; line <= 39; ++line)
        for (const MatchedRegion& m : p->regions)
            if (line >= (copyIsB ? m.firstB : m.firstA) && line <= (copyIsB ? m.lastB : m.lastA)) {
                ++matchedLines;
                break;
            }
    EXPECT_GE(matchedLines, 12);
}

TEST(Similarity, IndependentSolutionsAreNotFlagged) {
    const SimilarityReport r = findSimilarCode(corpus(), kStages, kStarter, SimilarityOptions());
    for (const SimilarPair& p : r.pairs)
        EXPECT_TRUE(r.names[p.a] == "reference" && r.names[p.b] == "copy_renamed")
            << p.stage << ": " << r.names[p.a] << " and " << r.names[p.b] << " flagged at " << p.score;
    EXPECT_EQ(r.pairs.size(), 4u);
}

// Two students who each wrote one different function of composite and left
// the rest as the starter code: the starter is all they share.
TEST(Similarity, TheStarterCodeDoesNotCount) {
    const std::string starter = readText(kStarter + "/composite/composite.glsl");
    const std::string todo =
        "    // TODO: implement this function (see the comment above it).\n    not_implemented();\n";
    const std::string stub = "vec4 classify_post(vec3 p) {\n" + todo + "    return vec4(0.0);\n}";
    ASSERT_NE(starter.find(stub), std::string::npos);
    std::string one = starter, two = starter;
    one.replace(one.find(stub), stub.size(),
                "vec4 classify_post(vec3 p) {\n    return transfer_function(sample_volume(p));\n}");
    const std::string jitter = "void jitter_start(inout Ray ray) {\n" + todo + "}";
    ASSERT_NE(two.find(jitter), std::string::npos);
    two.replace(two.find(jitter), jitter.size(),
                "void jitter_start(inout Ray ray) {\n    ray.t_entry += u_step * (pixel_random() - 0.5);\n}");
    const fs::path root = scratch("starter_only");
    writeText(root / "one/composite/composite.glsl", one);
    writeText(root / "two/composite/composite.glsl", two);
    writeText(root / "untouched/composite/composite.glsl", starter);
    const std::vector<SimilaritySubmission> subs = {{"one", (root / "one").string()}, {"two", (root / "two").string()},
                                                    {"untouched", (root / "untouched").string()}};
    const std::vector<SimilarityStage> stages = {{"composite", {"composite.glsl"}}};

    const SimilarityReport r = findSimilarCode(subs, stages, kStarter, everything());
    EXPECT_TRUE(r.pairs.empty()) << r.names[r.pairs[0].a] << " and " << r.names[r.pairs[0].b] << ": "
                                 << r.pairs[0].score;
    // Without the starter code set aside, the same three are all alike.
    const SimilarityReport without = findSimilarCode(subs, stages, (root / "no-starter").string(), SimilarityOptions());
    EXPECT_EQ(without.pairs.size(), 3u);
    ASSERT_FALSE(without.notes.empty());
    EXPECT_NE(without.notes[0].find("no starter code"), std::string::npos);
}

TEST(Similarity, FingerprintsOfMostOfTheClassAreSetAside) {
    // Twelve students hand in the same composite: past commonLimit (10), what
    // everybody has says nothing about any two of them.
    std::vector<SimilaritySubmission> subs;
    for (int i = 0; i < 12; ++i)
        subs.push_back({"s" + std::to_string(i), (kCorpus / "copy_renamed").string()});
    const std::vector<SimilarityStage> stages = {{"composite", {"composite.glsl"}}};
    EXPECT_TRUE(findSimilarCode(subs, stages, kStarter, SimilarityOptions()).pairs.empty());
    subs.resize(10);
    EXPECT_EQ(findSimilarCode(subs, stages, kStarter, SimilarityOptions()).pairs.size(), 45u);
}

// ---- bad input ------------------------------------------------------------------

TEST(Similarity, MalformedFilesAreLeftOutWithANote) {
    const fs::path root = scratch("malformed");
    const char binary[] = "float x;\0\x01\xff\xfe garbage";
    writeText(root / "binary/sampling/sampling.glsl", std::string(binary, sizeof binary - 1));
    writeText(root / "empty/sampling/sampling.glsl", "");
    writeText(root / "huge/sampling/sampling.glsl", std::string(300000, 'x'));
    writeText(root / "open_comment/sampling/sampling.glsl", "float sample_nearest(vec3 p) { /* never closed\n");
    fs::create_directories(root / "link/sampling");
    fs::create_symlink(kSource / "reference/sampling/sampling.glsl", root / "link/sampling/sampling.glsl");
    fs::create_directories(root / "folder/sampling/sampling.glsl");
    std::vector<SimilaritySubmission> subs;
    for (const char* n : {"binary", "empty", "huge", "open_comment", "link", "folder", "missing"})
        subs.push_back({n, (root / n).string()});
    subs.push_back({"reference", (kSource / "reference").string()});
    SimilarityOptions o = everything();
    o.maxFileBytes = 100000;
    const SimilarityReport r = findSimilarCode(subs, {{"sampling", {"sampling.glsl"}}}, kStarter, o);
    std::string notes;
    for (const std::string& n : r.notes) notes += n + "\n";
    EXPECT_NE(notes.find("binary: sampling/sampling.glsl: binary"), std::string::npos) << notes;
    EXPECT_NE(notes.find("huge: sampling/sampling.glsl: larger than 100000 bytes"), std::string::npos) << notes;
    EXPECT_NE(notes.find("link: sampling/sampling.glsl: a link"), std::string::npos) << notes;
    EXPECT_NE(notes.find("folder: sampling/sampling.glsl: not a regular file"), std::string::npos) << notes;
    EXPECT_EQ(notes.find("empty"), std::string::npos) << notes;
    EXPECT_EQ(notes.find("missing"), std::string::npos) << notes;
    EXPECT_TRUE(r.pairs.empty());  // the link's target (the reference itself) was not read
    EXPECT_TRUE(r.code[0][4].texts[0].empty());
    EXPECT_NO_THROW(similarityHtml(r));
}

TEST(Similarity, ALargeFileUnderTheCapIsQuick) {
    // 1 MiB of plausible code in each of two submissions.
    std::string big;
    for (int i = 0; big.size() < (std::size_t(1) << 20) - 100; ++i)
        big += "float v" + std::to_string(i) + " = max(a * " + std::to_string(i % 97) + ".5, b.x);\n";
    const fs::path root = scratch("large");
    writeText(root / "a/mip/mip.glsl", big);
    writeText(root / "b/mip/mip.glsl", big);
    const auto start = std::chrono::steady_clock::now();
    const SimilarityReport r = findSimilarCode({{"a", (root / "a").string()}, {"b", (root / "b").string()}},
                                               {{"mip", {"mip.glsl"}}}, kStarter, SimilarityOptions());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(r.pairs.size(), 1u);
    EXPECT_DOUBLE_EQ(r.pairs[0].score, 1.0);
    EXPECT_NO_THROW(similarityHtml(r));
    EXPECT_LT(seconds, 30.0);
}

// ---- the report -------------------------------------------------------------------

TEST(SimilarityReportFiles, JsonAndHtmlShowThePairsAsEvidence) {
    std::vector<SimilaritySubmission> subs = corpus();
    subs[1].name = "<b>mallory</b>";
    const SimilarityReport r = findSimilarCode(subs, kStages, kStarter, SimilarityOptions());
    const fs::path out = scratch("report");
    writeSimilarityReport(r, out.string());
    const nlohmann::json j = nlohmann::json::parse(readText(out / "similarity.json"));
    ASSERT_EQ(j["pairs"].size(), 4u);
    EXPECT_NE(j["about"].get<std::string>().find("not a verdict"), std::string::npos);
    const nlohmann::json& region = j["pairs"][0]["regions"][0];
    EXPECT_TRUE(region["a"]["lines"].is_array());
    EXPECT_EQ(j["method"]["threshold"], SimilarityOptions().threshold);
    const std::string html = readText(out / "similarity.html");
    EXPECT_NE(html.find("Evidence, not a verdict"), std::string::npos);
    EXPECT_EQ(html.find("<b>mallory"), std::string::npos);
    EXPECT_NE(html.find("&lt;b&gt;mallory"), std::string::npos);
    EXPECT_NE(html.find("class=\"l m0\""), std::string::npos);  // a highlighted line
    EXPECT_NE(html.find("texslice3d/proxy_geometry.cpp"), std::string::npos);
}

TEST(SimilarityReportFiles, TheThresholdOption) {
    EXPECT_FALSE(parseSimilarityThreshold("off"));
    EXPECT_DOUBLE_EQ(*parseSimilarityThreshold("0.7"), 0.7);
    EXPECT_DOUBLE_EQ(*parseSimilarityThreshold("1"), 1.0);
    for (const char* bad : {"", "0", "-0.5", "1.5", "abc", "0.5x", "nan"})
        EXPECT_THROW(parseSimilarityThreshold(bad), Error) << bad;
    // The command line refuses a bad value before grading anything.
    const fs::path root = scratch("cli");
    fs::create_directories(root / "class/alice");
    const CommandResult c = runVoxlab("grade --batch " + (root / "class").string() + " --out " +
                                      (root / "out").string() + " --similarity-threshold 2 --quiet");
    EXPECT_EQ(c.exitCode, 1) << c.out << c.err;
    EXPECT_NE(c.err.find("--similarity-threshold: must be a number in (0, 1]"), std::string::npos) << c.err;
    EXPECT_FALSE(fs::exists(root / "out" / "alice"));
}

}  // namespace
}  // namespace voxlab::testing
