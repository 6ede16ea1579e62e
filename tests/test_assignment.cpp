// Assignment files, upload layouts and Gradescope's exact sums
// (voxlab/assignment.h, grade_results.cpp).
//
// Oracles: dates against day counts worked out by hand from the calendar
// (1970-01-01 is day 0; 2000-03-01 is 11017 days later: 30 years of 365 days
// plus 7 leap days, plus the 31 + 29 days of January and February 2000);
// sums in hundredths against integer arithmetic on the scores written here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "voxlab/assignment.h"
#include "voxlab/error.h"
#include "voxlab/grader.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace voxlab;

namespace {

const std::string kReference = std::string(VOXLAB_SOURCE_DIR) + "/reference";

std::string writeTemp(const std::string& name, const std::string& text) {
    const fs::path p = fs::temp_directory_path() / ("voxlab_assignment_" + name);
    std::ofstream(p) << text;
    return p.string();
}

std::string loadError(const std::string& text) {
    try {
        loadAssignment(writeTemp("bad.json", text), kReference);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

long long cents(double x) { return std::llround(x * 100.0); }

}  // namespace

TEST(IsoTime, ReadsGradescopesAndInstructorsForms) {
    EXPECT_EQ(*parseIsoTime("1970-01-01T00:00:00Z"), 0.0);
    EXPECT_EQ(*parseIsoTime("2000-03-01"), 11017.0 * 86400.0);
    EXPECT_EQ(*parseIsoTime("2000-03-01T01:30Z"), 11017.0 * 86400.0 + 5400.0);
    // Eight hours west of UTC: the same instant as 08:00 UTC.
    EXPECT_EQ(*parseIsoTime("2000-03-01T00:00:00.000000-08:00"), 11017.0 * 86400.0 + 8 * 3600.0);
    EXPECT_NEAR(*parseIsoTime("2000-03-01T00:00:00.25+01:00"), 11017.0 * 86400.0 - 3600.0 + 0.25, 1e-6);
    for (const char* bad : {"", "2000", "2000-13-01", "2000-02-30", "2000-03-01T25:00Z", "2000-03-01T10:00+1",
                            "2000-03-01T10:00Zjunk", "yesterday", "2000-03-01T10:0"})
        EXPECT_FALSE(parseIsoTime(bad).has_value()) << bad;
}

TEST(AssignmentFile, EveryMistakeIsAnErrorNamingTheEntry) {
    EXPECT_NE(loadError("{").find("not a JSON object"), std::string::npos);
    EXPECT_NE(loadError(R"({"stages": []})").find("non-empty"), std::string::npos);
    EXPECT_NE(loadError(R"({"stages": [{"stage": "nosuchstage"}]})").find("unknown stage"), std::string::npos);
    EXPECT_NE(loadError(R"({"stages": [{"stage": "mip", "points": -1}]})").find("points"), std::string::npos);
    EXPECT_NE(loadError(R"({"stages": [{"stage": "mip"}, {"stage": "mip"}]})").find("twice"), std::string::npos);
    EXPECT_NE(loadError(R"({"stages": [{"stage": "mip", "visibility": "secret"}]})").find("visibility"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"stages": [{"stage": "mip", "visibility": {"no_scene": "hidden"}}]})").find("no_scene"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"stages": [{"stage": "mip"}], "due": "soon"})").find("ISO 8601"), std::string::npos);
    EXPECT_NE(loadError(R"({"stages": [{"stage": "mip"}], "late": {"penalty_per_day": 2}})").find("penalty"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"stages": [{"stage": "mip"}], "points": 3})").find("unknown key \"points\""),
              std::string::npos);
    EXPECT_EQ(loadError(R"({"stages": [{"stage": "mip", "points": 7}]})"), "");
}

TEST(AssignmentFile, VisibilityAndLatePolicyReachTheReport) {
    const Assignment a = loadAssignment(writeTemp("ok.json", R"({
        "stages": [{"stage": "mip", "visibility": {"mip_random_rays": "hidden"}}, {"stage": "minip", "visibility": "after_due_date"}],
        "hidden_scenes": "hidden", "due": "2026-12-01T00:00:00Z", "late": {"penalty_per_day": 0.25, "max_days": 2}})"),
                                        kReference);
    const json base = {{"score", 8.0},
                       {"stages",
                        {{{"stage", "mip"},
                          {"scenes", {{{"name", "a"}}, {{"name", "b"}, {"hidden", true}}}},
                          {"checks", {{{"name", "mip_random_rays"}}}}},
                         {{"stage", "minip"}, {"scenes", {{{"name", "c"}}}}, {"checks", json::array()}}}}};
    json r = base;
    applyAssignment(r, a, *parseIsoTime("2026-11-30T00:00:00Z"));
    EXPECT_EQ(r["stages"][0]["scenes"][0]["visibility"], "visible");
    EXPECT_EQ(r["stages"][0]["scenes"][1]["visibility"], "hidden");
    EXPECT_EQ(r["stages"][0]["checks"][0]["visibility"], "hidden");
    EXPECT_EQ(r["stages"][1]["scenes"][0]["visibility"], "after_due_date");
    EXPECT_EQ(r["score"], 8.0) << "on time";
    // 1 h late counts as one day: 8 x (1 - 0.25).
    r = base;
    applyAssignment(r, a, *parseIsoTime("2026-12-01T01:00:00Z"));
    EXPECT_DOUBLE_EQ(r["score"].get<double>(), 6.0);
    EXPECT_EQ(r["late"]["days"], 1.0);
    // Three days is past max_days: nothing. A due date given on the command line wins.
    r = base;
    applyAssignment(r, a, *parseIsoTime("2026-12-03T12:00:00Z"));
    EXPECT_EQ(r["score"], 0.0);
    r = base;
    applyAssignment(r, a, *parseIsoTime("2026-12-03T12:00:00Z"), *parseIsoTime("2026-12-04T00:00:00Z"));
    EXPECT_EQ(r["score"], 8.0);
}

// The tests' maxima and scores in cents, summed; no test above its maximum.
std::pair<long long, long long> centSums(const json& results) {
    long long max = 0, score = 0;
    for (const json& t : results["tests"]) {
        max += cents(t["max_score"]);
        score += cents(t["score"]);
        EXPECT_LE(cents(t["score"]), cents(t["max_score"])) << t.dump();
    }
    return {max, score};
}

// Three items of 10/3 points each used to show 3.33 + 3.33 + 3.33 = 9.99.
TEST(GradescopeResults, ScoresOfAStageAddUpExactly) {
    const double third = 10.0 / 3.0;
    const json report = {
        {"score", 2.0 * third + 0.5 * third},
        {"max_score", 10.0},
        {"stages",
         {{{"stage", "s"},
           {"title", "S"},
           {"max_score", 10.0},
           {"score", 2.0 * third + 0.5 * third},
           {"scenes",
            {{{"name", "a"}, {"status", "passed"}, {"max_score", third}, {"score", third}},
             {{"name", "b"}, {"status", "passed"}, {"max_score", third}, {"score", third}},
             {{"name", "c"}, {"status", "failed"}, {"max_score", third}, {"score", 0.5 * third}}}},
           {"checks", json::array()}}}}};
    const json r = gradescopeResults(report);
    const auto [max, score] = centSums(r);
    for (const json& t : r["tests"]) EXPECT_LT(std::abs(t["max_score"].get<double>() - third), 0.01) << t.dump();
    EXPECT_EQ(max, 1000);
    EXPECT_EQ(score, 833);  // 8.333... rounded once
    EXPECT_EQ(cents(r["score"]), 833);
    // A full-marks item shows its full points.
    EXPECT_EQ(r["tests"][0]["score"], r["tests"][0]["max_score"]);
    EXPECT_EQ(r["tests"][1]["score"], r["tests"][1]["max_score"]);
}

// Six items of 4/3 points (a stage of 8): the maxima round to 1.34, 1.34,
// 1.33, 1.33, 1.33, 1.33. With the first three at full marks the stage
// scored 4.00, but their rounded maxima add up to 4.01: the tests used to
// say 4.01.
TEST(GradescopeResults, FullMarksItemsNeverAddUpToMoreThanTheStage) {
    const double item = 4.0 / 3.0;
    json scenes = json::array();
    for (int i = 0; i < 6; ++i)
        scenes.push_back({{"name", std::string(1, char('a' + i))}, {"status", i < 3 ? "passed" : "failed"},
                          {"max_score", item}, {"score", i < 3 ? item : 0.0}});
    const json report = {{"score", 3.0 * item}, {"max_score", 8.0},
                         {"stages", {{{"stage", "s"}, {"title", "S"}, {"max_score", 8.0}, {"score", 3.0 * item},
                                      {"scenes", scenes}, {"checks", json::array()}}}}};
    const json r = gradescopeResults(report);
    const auto [max, score] = centSums(r);
    for (const json& t : r["tests"])
        if (t["status"] == "passed") EXPECT_GE(cents(t["score"]), cents(t["max_score"]) - 1) << t.dump();
    EXPECT_EQ(max, 800);
    EXPECT_EQ(score, 400);
    EXPECT_EQ(cents(r["score"]), 400);
}

TEST(SubmissionLayout, FindsNestedFoldersAndPlacesLooseFiles) {
    const fs::path up = fs::temp_directory_path() / "voxlab_layout_test";
    fs::remove_all(up);
    fs::create_directories(up / "release" / "assignments" / "mip");
    std::ofstream(up / "release" / "assignments" / "mip" / "mip.glsl") << "x";
    std::string note;
    const std::vector<std::string> stages = {"mip", "minip"};
    EXPECT_EQ(submissionRoot(up.string(), kReference, stages, (up / "staging").string(), &note),
              (up / "release" / "assignments").string());
    EXPECT_NE(note.find("release/assignments"), std::string::npos) << note;
    // Loose files (and a symbolic link, which is never followed).
    fs::remove_all(up);
    fs::create_directories(up / "sub");
    std::ofstream(up / "sub" / "minip.glsl") << "y";
    fs::create_directory_symlink("/etc", up / "link");
    const std::string root = submissionRoot(up.string(), kReference, stages, (up / "staging").string(), &note);
    EXPECT_EQ(root, (up / "staging").string());
    EXPECT_TRUE(fs::is_regular_file(up / "staging" / "minip" / "minip.glsl"));
    EXPECT_FALSE(fs::exists(up / "staging" / "mip"));
    EXPECT_NE(note.find("minip.glsl -> minip/"), std::string::npos) << note;
    // Already in shape: unchanged, no note.
    fs::remove_all(up);
    fs::create_directories(up / "mip");
    std::ofstream(up / "mip" / "mip.glsl") << "x";
    EXPECT_EQ(submissionRoot(up.string(), kReference, stages, (up / "staging").string(), &note), up.string());
    EXPECT_EQ(note, "");
    fs::remove_all(up);
}
