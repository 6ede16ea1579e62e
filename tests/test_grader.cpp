// The grader end to end (voxlab/grader.h): the reference scores full marks,
// the starter code scores zero with "not implemented", and a submission that
// hangs, crashes or does not compile is graded in bounded time with clear
// messages, without touching anything outside its report folder.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "voxlab/error.h"
#include "voxlab/grader.h"
#include "voxlab/grading.h"
#include "voxlab/scene.h"
#include "voxlab/stage_library.h"
#include "support/expected_outputs.h"
#include "support/run_command.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSource = VOXLAB_SOURCE_DIR;

fs::path scratchPath(const std::string& name) {
    return fs::path(::testing::TempDir()) / ("voxlab_grader_" + std::to_string(getpid())) / name;
}

fs::path scratch(const std::string& name) {
    const fs::path dir = scratchPath(name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Copies reference/ and replaces `find` (which must occur once) in one file.
fs::path mutatedCopy(const fs::path& into, const std::string& file, const std::string& find,
                     const std::string& replace) {
    fs::copy(kSource / "reference", into, fs::copy_options::recursive);
    const fs::path path = into / file;
    std::string text = readFile(path);
    const std::size_t at = text.find(find);
    EXPECT_NE(at, std::string::npos) << file << ": '" << find << "' not found";
    EXPECT_EQ(text.find(find, at + 1), std::string::npos) << file << ": '" << find << "' occurs twice";
    if (at != std::string::npos) text.replace(at, find.size(), replace);
    std::ofstream(path) << text;
    return into;
}

// A fingerprint of a folder: every file's path, size and content.
std::string fingerprint(const fs::path& root) {
    std::vector<std::string> entries;
    for (const auto& e : fs::recursive_directory_iterator(root))
        if (e.is_regular_file()) entries.push_back(fs::relative(e.path(), root).string() + "\n" + readFile(e.path()));
    std::sort(entries.begin(), entries.end());
    std::string all;
    for (const std::string& s : entries) all += s;
    return std::to_string(all.size()) + ":" + std::to_string(std::hash<std::string>{}(all));
}

// The reference's expected outputs are rendered once for the whole file.
class Grader : public ExpectedOutputsSuite<Grader> {
public:
    static fs::path expectedFolder() { return scratch("expected"); }
    // Everything the file wrote goes with it (reports of hundreds of images).
    static void TearDownTestSuite() { fs::remove_all(scratchPath("").parent_path()); }
    static GraderOptions options() {
        GraderOptions o = referenceOptions();
        o.jobs = 2;
        return o;
    }
    static json grade(const fs::path& folder, const std::string& name, GraderOptions o = options()) {
        return gradeSubmissions({{name, folder.string(), scratch("report_" + name).string()}}, o).at(0);
    }
    static const json& stage(const json& report, const std::string& id) {
        for (const json& s : report["stages"])
            if (s["stage"] == id) return s;
        throw Error("no stage " + id + " in the report");
    }
};

TEST_F(Grader, TheReferenceScoresFullMarks) {
    const json report = grade(kSource / "reference", "reference");
    ASSERT_EQ(report["stages"].size(), gradedStages((kSource / "reference").string()).size());
    for (const json& s : report["stages"]) {
        EXPECT_TRUE(s["status"] == "passed" || s["status"] == "example") << s["stage"] << ": " << s["message"];
        EXPECT_DOUBLE_EQ(s["score"].get<double>(), s["max_score"].get<double>()) << s["stage"];
    }
    EXPECT_GT(report["max_score"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(report["score"].get<double>(), report["max_score"].get<double>());
}

TEST_F(Grader, ThePristineAssignmentsScoreZeroAndSayNotImplemented) {
    const json report = grade(kSource / "assignments", "pristine");
    for (const json& s : report["stages"]) {
        if (s["stage"] == "slicer") {  // the worked example: complete in the starter code, worth no points
            EXPECT_EQ(s["status"], "example");
            EXPECT_EQ(s["max_score"].get<double>(), 0.0);
            continue;
        }
        EXPECT_EQ(s["status"], "not_implemented") << s["stage"] << ": " << s["message"];
        EXPECT_EQ(s["score"].get<double>(), 0.0) << s["stage"];
        EXPECT_NE(s["message"].get<std::string>().find("not yet implemented"), std::string::npos) << s["message"];
    }
    EXPECT_EQ(report["score"].get<double>(), 0.0);
}

// llvmpipe ends every shader loop after 65535 rounds, so a loop whose
// counter never grows finishes with wrong pixels instead of hanging. It must
// still be called a time-out, which it would be on a GPU: the worker counts
// the first scene's samples against the sampling rule.
TEST_F(Grader, ALoopThatNeverEndsIsATimeoutEvenWhenLlvmpipeCutsItShort) {
    const fs::path root = scratch("runaway");
    const fs::path sub = root / "submission";
    fs::create_directories(sub / "mip");
    std::string text = readFile(kSource / "reference" / "mip" / "mip.glsl");
    const std::string loop = "for (int m = 0; m < n; ++m)";
    ASSERT_NE(text.find(loop), std::string::npos);
    text.replace(text.find(loop), loop.size(), "for (int m = 0; m < n; m += 0)");
    std::ofstream(sub / "mip" / "mip.glsl") << text;
    GraderOptions o = options();
    o.stages = {"mip"};
    const json report = grade(sub, "runaway", o);
    const json& mip = stage(report, "mip");
    EXPECT_EQ(mip["status"], "timeout") << mip["message"];
    EXPECT_NE(mip["message"].get<std::string>().find("a loop ran away"), std::string::npos) << mip["message"];
    EXPECT_EQ(mip["score"].get<double>(), 0.0);
    // Found before any scene renders, on a 48-pixel copy of the first
    // scene, by a count of samples, not a time: no scene then runs its
    // 65 535 rounds a pixel (on a loaded machine they ran into the limit).
    EXPECT_NE(mip["message"].get<std::string>().find("at 48x48"), std::string::npos) << mip["message"];
    for (const json& scene : mip["scenes"])
        EXPECT_NE(scene["message"].get<std::string>().find("not rendered: a loop ran away"), std::string::npos)
            << scene["name"] << ": " << scene["message"];
    std::printf("a runaway MIP graded in %.2f s\n", mip["elapsed_s"].get<double>());
    // The reference's own loop is not a runaway.
    const json good = grade(kSource / "reference", "reference", o);
    EXPECT_EQ(stage(good, "mip")["status"], "passed") << stage(good, "mip")["message"];
}

TEST_F(Grader, HangsCrashesAndCompileErrorsAreReportedInBoundedTime) {
    const fs::path root = scratch("broken");
    const fs::path sub = root / "submission";
    fs::copy(kSource / "reference", sub, fs::copy_options::recursive);
    auto edit = [&](const std::string& file, const std::string& find, const std::string& replace) {
        std::string text = readFile(sub / file);
        const std::size_t at = text.find(find);
        ASSERT_NE(at, std::string::npos) << file << ": " << find;
        text.replace(at, find.size(), replace);
        std::ofstream(sub / file) << text;
    };
    // mip: a loop that never ends (a sample is never below -1), whose result
    // is used, so that the compiler cannot drop it.
    edit("mip/mip.glsl", "// BEGIN SOLUTION",
         "// BEGIN SOLUTION\n    vec3 wander = ray.origin;\n"
         "    while (sample_volume(wander) > -1.0) wander.x += 0.001;\n    if (wander.x > 0.0) return wander.x;");
    // composite: a syntax error (a missing semicolon) on a known line.
    edit("composite/composite.glsl", "// BEGIN SOLUTION", "// BEGIN SOLUTION\n    float oops = 1.0");
    // texslice3d: a crash in C++.
    edit("texslice3d/proxy_geometry.cpp", "// BEGIN SOLUTION",
         "// BEGIN SOLUTION\n    if (normal.x > -2.0) *(volatile int*)nullptr = 1;");
    // texslice2d: C++ that does not compile.
    edit("texslice2d/slice_axis.cpp", "// BEGIN SOLUTION", "// BEGIN SOLUTION\n    int x = undeclared_thing;");
    const std::string referenceBefore = fingerprint(kSource / "reference");

    GraderOptions o = options();
    o.timeLimit = 8.0;
    o.stages = {"mip", "composite", "texslice2d", "texslice3d"};
    const auto start = std::chrono::steady_clock::now();
    const json report = grade(sub, "broken", o);
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Four stages on two workers, the hang costing its 8 s limit, plus
    // compiling C++ twice: well under a minute.
    EXPECT_LT(took, 60.0);

    const json& mip = stage(report, "mip");
    EXPECT_EQ(mip["status"], "timeout") << mip["message"];
    EXPECT_NE(mip["message"].get<std::string>().find("timed out after 8 s"), std::string::npos) << mip["message"];
    EXPECT_EQ(mip["score"].get<double>(), 0.0);

    const json& composite = stage(report, "composite");
    EXPECT_EQ(composite["status"], "compile_error") << composite["message"];
    // The compiler's message names the student's file and the line after the
    // unterminated statement, relative to the submission.
    const std::string log = composite.value("log", "");
    EXPECT_EQ(log.rfind("composite/composite.glsl:", 0), 0u) << log;
    EXPECT_EQ(composite["score"].get<double>(), 0.0);

    const json& slab = stage(report, "texslice2d");
    EXPECT_EQ(slab["status"], "compile_error");
    EXPECT_NE(slab.value("log", "").find("texslice2d/slice_axis.cpp:"), std::string::npos) << slab.value("log", "");
    EXPECT_NE(slab.value("log", "").find("undeclared_thing"), std::string::npos);

    const json& crash = stage(report, "texslice3d");
    EXPECT_EQ(crash["status"], "crashed") << crash["message"];
#if defined(__SANITIZE_ADDRESS__) || defined(VOXLAB_SANITIZED)
    // Under AddressSanitizer the stage host reports the fault itself and exits 1.
    const std::string how = "exit status 1";
#else
    const std::string how = "Segmentation fault";
#endif
    EXPECT_NE(crash["message"].get<std::string>().find(how), std::string::npos) << crash["message"];

    EXPECT_EQ(fingerprint(kSource / "reference"), referenceBefore) << "grading changed reference/";
}

// Stage libraries are built with the standard and GLM headers precompiled
// (framework/stage_library/stage_prelude.h). A file that configures GLM
// before including it (swizzles here) means something else with those
// headers already read: it must be built as written, and pass.
TEST_F(Grader, AStageFileThatConfiguresGlmFirstIsBuiltAsWritten) {
    const fs::path root = scratch("glm_first");
    const fs::path sub = mutatedCopy(root / "submission", "texslice2d/slice_axis.cpp",
                                     "glm::abs(viewDirection)", "glm::abs(viewDirection.xyz())");
    const std::string text = readFile(sub / "texslice2d/slice_axis.cpp");
    std::ofstream(sub / "texslice2d/slice_axis.cpp") << "#define GLM_FORCE_SWIZZLE\n" << text;
    GraderOptions o = options();
    o.stages = {"texslice2d"};
    const json report = grade(sub, "glm_first", o);
    const json& s = stage(report, "texslice2d");
    EXPECT_EQ(s["status"], "passed") << s["message"] << "\n" << s.value("log", "");
    EXPECT_DOUBLE_EQ(s["score"].get<double>(), s["max_score"].get<double>());
}

// The prelude is worth having only if the compiler takes the .gch: built
// with other flags than the stage build's, it is silently parsed instead.
// -H marks a precompiled header it used with "!".
TEST(StagePrelude, TheCompilerUsesThePrecompiledHeader) {
#ifdef __clang__
    GTEST_SKIP() << "clang's -H does not mark the precompiled header it used (it builds and uses one the same way)";
#endif
    const std::string prelude = stagePreludeHeader();
    ASSERT_FALSE(prelude.empty()) << "the build made no precompiled stage prelude";
    const fs::path out = scratch("prelude") / "splat.so";
    std::string command;
    for (const std::string& word : stageLibraryBuildCommand({(kSource / "reference/splat/splat_order.cpp").string()},
                                                            out.string(), prelude))
        command += "'" + word + "' ";
    const CommandResult r = runShell(command + "-H");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("! " + prelude + ".gch"), std::string::npos) << r.err.substr(0, 2000);
    EXPECT_TRUE(fs::exists(out));
}

TEST_F(Grader, ASubmissionCannotWriteOutsideItsReportFolder) {
    const fs::path root = scratch("writer");
    const fs::path target = root / "escaped.txt";
    const fs::path sub = mutatedCopy(root / "submission", "texslice3d/proxy_geometry.cpp", "// BEGIN SOLUTION",
                                     "// BEGIN SOLUTION\n    if (FILE* f = std::fopen(\"" + target.string() +
                                         "\", \"w\")) { std::fputs(\"x\", f); std::fclose(f); }");
    // <cstdio> for the write above.
    std::string text = readFile(sub / "texslice3d/proxy_geometry.cpp");
    std::ofstream(sub / "texslice3d/proxy_geometry.cpp") << "#include <cstdio>\n" << text;
    GraderOptions o = options();
    o.stages = {"texslice3d"};
    const json report = grade(sub, "writer", o);
    const json layers = report.at("sandbox");
    if (std::find(layers.begin(), layers.end(), "landlock writes") == layers.end()) GTEST_SKIP() << "no Landlock here";
    EXPECT_FALSE(fs::exists(target)) << "the submission wrote " << target;
    // The stage itself still renders: only the write failed.
    EXPECT_EQ(stage(report, "texslice3d")["status"], "passed") << stage(report, "texslice3d")["message"];
}

// Hidden scenes: graded (Gradescope shows them after the due date), but not
// part of a self-check, of the starter code or of a release's goldens.
TEST_F(Grader, HiddenScenesAreGradedButNeverShipped) {
    GraderOptions o = options();
    o.stages = {"mip"};
    const json graded = grade(kSource / "reference", "hidden", o);
    bool found = false;
    for (const json& scene : stage(graded, "mip")["scenes"])
        if (scene["name"] == "ct_signed_air") found = scene["hidden"] == true && scene["status"] == "passed";
    EXPECT_TRUE(found) << stage(graded, "mip").dump(1);
    const json results = json::parse(readFile(scratchPath("report_hidden") / "results.json"));
    int later = 0;
    for (const json& t : results["tests"])
        if (t["visibility"] == "after_due_date") {
            ++later;
            EXPECT_NE(t["name"].get<std::string>().find("ct_signed_air"), std::string::npos) << t["name"];
        }
    EXPECT_EQ(later, 1);
    o.hiddenScenes = false;
    const json visible = grade(kSource / "reference", "visible", o);  // outlives the loop over its scenes
    for (const json& scene : stage(visible, "mip")["scenes"]) EXPECT_NE(scene["name"], "ct_signed_air");
    // The starter code: no hidden scene in any manifest, none of their files.
    for (const std::string& s : gradedStages((kSource / "reference").string()))
        for (const GradedScene& scene : loadStageManifest((kSource / "reference").string(), s).scenes) {
            if (!scene.hidden) continue;
            const fs::path shipped = kSource / "assignments" / s / fs::relative(scene.scenePath, kSource / "reference" / s);
            EXPECT_FALSE(fs::exists(shipped)) << shipped;
            for (const GradedScene& a : loadStageManifest((kSource / "assignments").string(), s).scenes)
                EXPECT_NE(a.name, scene.name) << s;
        }
}

TEST_F(Grader, GradescopeResultsFollowTheFormat) {
    const fs::path sub = mutatedCopy(scratch("gs") / "submission", "mip/mip.glsl", "// BEGIN SOLUTION",
                                     "// BEGIN SOLUTION\n    return 0.5;");
    GraderOptions o = options();
    o.stages = {"mip", "minip"};
    const json report = grade(sub, "gs", o);
    const json results = json::parse(readFile(scratchPath("report_gs") / "results.json"));
    ASSERT_TRUE(results.contains("score"));
    ASSERT_TRUE(results["tests"].is_array());
    double sum = 0.0;
    for (const json& t : results["tests"]) {
        for (const char* key : {"name", "score", "max_score", "status", "output", "visibility"})
            EXPECT_TRUE(t.contains(key)) << key;
        EXPECT_TRUE(t["status"] == "passed" || t["status"] == "failed");
        sum += t["score"].get<double>();
    }
    EXPECT_NEAR(sum, results["score"].get<double>(), 0.05);
    EXPECT_NEAR(results["score"].get<double>(), 10.0, 0.05) << "minip full, mip (returns 0.5 everywhere) zero";
    EXPECT_EQ(stage(report, "mip")["status"], "failed");
}

TEST(GradingManifest, BadManifestsGiveOneLineErrors) {
    const fs::path root = scratch("manifests");
    fs::create_directories(root / "mip");
    auto expectError = [&](const std::string& text, const std::string& needle) {
        std::ofstream(root / "mip" / "grading.json") << text;
        try {
            loadStageManifest(root.string(), "mip");
            ADD_FAILURE() << "no error for " << text;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    };
    expectError("{", "grading.json");
    expectError(R"({"points": 10})", "title: missing");
    expectError(R"({"title": "x", "points": 10})", "order: required");
    expectError(R"({"title": "x", "order": 1, "scenes": [{"name": "a/b", "scene": "s.json"}]})", "name");
    expectError(R"({"title": "x", "order": 1, "scenes": [{"name": "a", "scene": "s.json", "tolerance": {"max_flp": 1}}]})",
                "unknown key 'max_flp'");
    expectError(R"({"title": "x", "order": 1, "scenes": [{"name": "a", "scene": "s.json", "hidden": "yes"}]})",
                "hidden: expected true or false");
    expectError(R"({"title": "x", "order": 1, "cpp_functions": ["planeBoxPolygonn"]})",
                "'planeBoxPolygonn' is not a C++ stage function");
    expectError(R"({"title": "x", "order": 1, "files": ["../mip.glsl"]})", "is not a plain");
    expectError(R"({"title": "x", "order": 1, "files": []})", "functions: required for a graded stage");
    expectError(R"({"title": "x", "order": 1, "files": [], "functions": ["mip_ray"],
                    "scenes": [{"name": "a", "scene": "s.json", "functions": ["mip_rays"]}]})",
                "'mip_rays' is not one of the stage's functions");
    expectError(R"({"title": "x", "order": 1, "files": [], "functions": ["mip_ray"],
                    "hints": [{"failed": ["nosuchscene"], "hints": ["Looks like"]}]})",
                "'nosuchscene' is not a scene or check of this stage");
    // A misspelt key at any level is an error, not a setting quietly ignored.
    expectError(R"({"title": "x", "order": 1, "tolerances": {"min_ssim": 0.5}})", "unknown key 'tolerances'");
    expectError(R"({"title": "x", "order": 1, "scenes": [{"name": "a", "scene": "s.json", "wieght": 2}]})",
                "unknown key 'wieght'");
    expectError(R"({"title": "x", "order": 1, "checks": [{"name": "c", "hidden": true}]})", "unknown key 'hidden'");
    expectError(R"({"title": "x", "order": 1, "points": 0, "hints": [{"failed": [], "hint": "x"}]})", "unknown key 'hint'");
    expectError(R"({"title": "x", "order": 1, "tolerance": {"min_ssim": 2}})", "tolerance: tolerances out of range");
    EXPECT_THROW(loadStageManifest(root.string(), "nosuchstage"), Error);
}

// Tolerances in three layers: the defaults, the manifest's stage-wide
// "tolerance", a scene's own keys; each sets only the keys it names.
TEST(GradingManifest, StageWideToleranceUnderSceneTolerance) {
    const fs::path root = scratch("manifest_tolerance");
    fs::create_directories(root / "mip");
    std::ofstream(root / "mip" / "grading.json") << R"({"title": "x", "order": 1, "points": 0,
        "tolerance": {"min_ssim": 0.9, "max_flip": 0.05},
        "scenes": [{"name": "a", "scene": "a.json"}, {"name": "b", "scene": "b.json", "tolerance": {"max_flip": 0.1}}]})";
    const StageManifest m = loadStageManifest(root.string(), "mip");
    const Tolerance defaults;
    ASSERT_EQ(m.scenes.size(), 2u);
    EXPECT_EQ(m.scenes[0].tolerance.minSsim, 0.9);
    EXPECT_EQ(m.scenes[0].tolerance.maxFlip, 0.05);
    EXPECT_EQ(m.scenes[0].tolerance.maxDifference, defaults.maxDifference);
    EXPECT_EQ(m.scenes[1].tolerance.minSsim, 0.9) << "the scene's keys replaced the stage's other keys";
    EXPECT_EQ(m.scenes[1].tolerance.maxFlip, 0.1);
    // --tolerance over a scene's: only its keys.
    const Tolerance t = overTolerance(m.scenes[1].tolerance, json{{"max_difference", 8}}, "--tolerance");
    EXPECT_EQ(t.maxDifference, 8.0);
    EXPECT_EQ(t.maxFlip, 0.1);
    EXPECT_THROW(overTolerance(t, json{{"min_sim", 0.5}}, "--tolerance"), Error);
}

// The manifest's functions must be defined in the stage's files, and its
// prerequisites must be stages: one-line errors naming the manifest.
TEST(GradingManifest, FunctionsAndPrerequisitesMustExist) {
    const fs::path root = scratch("manifest_functions");
    fs::create_directories(root / "mip");
    std::ofstream(root / "mip" / "mip.glsl") << "float mip_ray(Ray ray) { return 0.0; }\n";
    std::ofstream(root / "mip" / "grading.json")
        << R"({"title": "x", "order": 1, "functions": ["mip_ray", "minip_ray"]})";
    const auto message = [](auto f) {
        try {
            f();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const StageManifest m = loadStageManifest(root.string(), "mip");
    EXPECT_NE(message([&] { checkStageFunctions(m, root.string()); }).find("'minip_ray' is not defined in the stage's files"),
              std::string::npos);
    EXPECT_NE(message([&] { stageManifests(root.string()); }).find("minip_ray"), std::string::npos);
    std::ofstream(root / "mip" / "grading.json")
        << R"({"title": "x", "order": 1, "functions": ["mip_ray"], "requires": ["sampling"]})";
    EXPECT_NE(message([&] { stageManifests(root.string()); }).find("requires: no stage 'sampling'"), std::string::npos);
    std::ofstream(root / "mip" / "grading.json") << R"({"title": "x", "order": 1, "functions": ["mip_ray"]})";
    EXPECT_EQ(message([&] { stageManifests(root.string()); }), "no error");
    // Only the whole name followed by "(" counts: not inside a longer name.
    std::ofstream(root / "mip" / "mip.glsl") << "float xmip_ray(Ray r) { return mip_ray_x(r) + mip_ray; }\n";
    EXPECT_NE(message([&] { stageManifests(root.string()); }).find("'mip_ray' is not defined"), std::string::npos);
    std::ofstream(root / "mip" / "mip.glsl") << "float xmip_ray(Ray r);\nfloat mip_ray \n  (Ray ray) { return 0.0; }\n";
    EXPECT_EQ(message([&] { stageManifests(root.string()); }), "no error");
}

TEST(GradingCredit, AFailedItemEarnsAtMostHalfFallingToZeroAtThreeTimesTheThreshold) {
    EXPECT_EQ(creditForRatio(0.0), 1.0);
    EXPECT_EQ(creditForRatio(1.0), 1.0);
    EXPECT_NEAR(creditForRatio(1.0 + 1e-9), 0.5, 1e-9);
    EXPECT_DOUBLE_EQ(creditForRatio(2.0), 0.25);
    EXPECT_DOUBLE_EQ(creditForRatio(2.5), 0.125);
    EXPECT_EQ(creditForRatio(3.0), 0.0);
    EXPECT_EQ(creditForRatio(1e9), 0.0);
    // Function checks: full credit only with no failing case, at most half
    // with one, none from 10%.
    EXPECT_EQ(creditForFailedCases(0.0), 1.0);
    EXPECT_NEAR(creditForFailedCases(1e-9), 0.5, 1e-6);
    EXPECT_DOUBLE_EQ(creditForFailedCases(0.05), 0.25);
    EXPECT_EQ(creditForFailedCases(0.1), 0.0);
    EXPECT_EQ(creditForFailedCases(0.8), 0.0);
    // The worst metric decides; SSIM counts by 1 - SSIM.
    Tolerance t;
    ImageMetrics m;
    m.fractionOver = 0.5 * t.maxFraction;
    m.ssim = 1.0 - 2.0 * (1.0 - t.minSsim);
    m.flipMean = 0.1 * t.maxFlip;
    EXPECT_DOUBLE_EQ(toleranceRatio(m, t), 2.0);
}

// "Small regions count": a thin feature wrong by 77 levels on 0.37% of the
// pixels used to pass (under the 0.5% allowed to be anything); the same
// number of wrong pixels scattered one by one, as rasterisation noise is,
// still passes.
TEST(GradingCredit, ACompactGroupOfWrongPixelsFailsWhereScatteredOnesPass) {
    const Tolerance t;
    Image expected(128, 128), thin(128, 128), scattered(128, 128);
    for (Image* img : {&expected, &thin, &scattered})
        for (std::size_t i = 0; i < img->rgba.size(); ++i) img->rgba[i] = (i % 4 == 3) ? 1.0f : 0.4f;
    auto set = [](Image& img, int x, int y) {
        for (int c = 0; c < 3; ++c) img.rgba[(std::size_t(y) * 128 + x) * 4 + c] = 0.4f + 77.0f / 255.0f;
    };
    for (int i = 0; i < 60; ++i) set(thin, 30 + i, 40 + i / 3);               // a thin line of 60 pixels
    for (int i = 0; i < 60; ++i) set(scattered, 3 + (i % 10) * 12, 5 + (i / 10) * 20);  // 60 lone pixels
    const ImageMetrics line = compareForGrading(expected, thin, t);
    const ImageMetrics noise = compareForGrading(expected, scattered, t);
    // The old rule alone let both pass.
    EXPECT_LT(line.fractionOver, t.maxFraction);
    EXPECT_LT(noise.fractionOver, t.maxFraction);
    // The cluster bound alone fails the line outright and lets lone pixels be.
    EXPECT_EQ(line.largestCluster, 60);
    EXPECT_GE(line.largestCluster / t.maxCluster, 3.0);
    EXPECT_EQ(creditForRatio(toleranceRatio(line, t)), 0.0);
    EXPECT_EQ(noise.largestCluster, 1);
    EXPECT_LE(noise.largestCluster / t.maxCluster, 1.0);
}

// The stages are what the manifests declare: a new stage folder with a
// manifest is graded, in its order; a manifest without an order is an error.
TEST(StageManifests, EveryStageWithAManifestIsGradedInItsOrder) {
    const fs::path root = scratch("manifests");
    fs::copy(kSource / "reference", root, fs::copy_options::recursive);
    const std::vector<std::string> before = gradedStages(root.string());
    EXPECT_EQ(before.front(), "slicer");
    std::size_t folders = 0;  // counted here, from the folders themselves
    for (const auto& entry : fs::directory_iterator(root)) folders += fs::exists(entry.path() / "grading.json");
    EXPECT_EQ(before.size(), folders);
    fs::copy(root / "mip", root / "mystage", fs::copy_options::recursive);
    std::string manifest = readFile(root / "mystage/grading.json");
    const std::string three = "\"order\": 3,", ninetyNine = "\"order\": 99,";
    manifest.replace(manifest.find(three), three.size(), ninetyNine);
    std::ofstream(root / "mystage/grading.json") << manifest;
    std::vector<std::string> after = gradedStages(root.string());
    ASSERT_EQ(after.size(), folders + 1);
    EXPECT_EQ(after.back(), "mystage");
    manifest.replace(manifest.find(ninetyNine), ninetyNine.size(), "");
    std::ofstream(root / "mystage/grading.json") << manifest;
    try {
        gradedStages(root.string());
        ADD_FAILURE() << "a manifest without an order was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("mystage/grading.json: order: required"), std::string::npos) << e.what();
    }
}

TEST(StubScan, NamesTheFunctionsStillStubbed) {
    EXPECT_EQ(unimplementedFunctions((kSource / "assignments/composite").string()),
              (std::vector<std::string>{"classify_post", "classify_pre", "jitter_start", "composite_front_to_back",
                                        "composite_back_to_front"}));
    EXPECT_EQ(unimplementedFunctions((kSource / "assignments/texslice3d").string()),
              std::vector<std::string>{"planeBoxPolygon"});
    for (const std::string& s : gradedStages((kSource / "reference").string()))
        EXPECT_TRUE(unimplementedFunctions((kSource / "reference" / s).string()).empty()) << s;
}

// The stub scan runs in the grader on the submission's own files. With
// std::regex it overflowed the stack (SIGSEGV) on a line of 200 000 spaces.
TEST(StubScan, ALineOf200000SpacesIsScannedWithoutOverflowingTheStack) {
    const fs::path dir = fs::path(::testing::TempDir()) / ("voxlab_stub_scan_" + std::to_string(getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "stage.glsl") << "float mip_ray(Ray r) {\n    not_implemented();\n}\n"
                                      << std::string(200000, ' ') << "\n"
                                      << std::string(200000, 'x') << "\n"
                                      << "std::vector<glm::vec3> planeBoxPolygon(const Plane& p,\n"
                                      << "                                       int n) {\n"
                                      << "\tthrow   NotImplemented (\"planeBoxPolygon\");\n}\n"
                                      << "const float* weird_name_2 (int) {\n  not_implemented ( ) ;\n}\n"
                                      << "int x = helper(\n  not_implemented();\n"  // not a signature: '='
                                      << "vec4 done(vec4 c) { return c; }\n  not_implementedX();\n";
    EXPECT_EQ(unimplementedFunctions(dir.string()),
              (std::vector<std::string>{"mip_ray", "planeBoxPolygon", "weird_name_2"}));
    fs::remove_all(dir);
}

// The command line: a class graded with --batch gives a gradebook and a
// class report; `voxlab check` exits 0 only when the stages checked pass.
TEST(GradeCommand, BatchWritesAGradebookAndCheckSaysWhatIsMissing) {
    const fs::path root = scratch("cli");
    fs::create_directories(root / "class" / "bob" / "minip");
    fs::create_directories(root / "class" / "carol" / "minip");
    fs::copy(kSource / "reference" / "minip", root / "class" / "bob" / "minip", fs::copy_options::recursive);
    fs::copy(kSource / "assignments" / "minip", root / "class" / "carol" / "minip", fs::copy_options::recursive);
    const CommandResult batch = runVoxlab("grade --batch " + (root / "class").string() + " --stage minip --out " +
                                              (root / "reports").string() + " --jobs 2 --quiet",
                                          300);
    ASSERT_EQ(batch.exitCode, 0) << batch.err;
    const std::string csv = readFile(root / "reports" / "gradebook.csv");
    EXPECT_NE(csv.find("name,score,max_score,minip,problems"), std::string::npos) << csv;
    EXPECT_NE(csv.find("bob,10.00,10.00,10.00,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("carol,0.00,10.00,0.00,minip: not_implemented"), std::string::npos) << csv;
    EXPECT_TRUE(fs::exists(root / "reports" / "index.html"));
    EXPECT_TRUE(fs::exists(root / "reports" / "bob" / "index.html"));

    const CommandResult good = runVoxlab("check --stage minip --submission " + (root / "class" / "bob").string() +
                                             " --out " + (root / "check_bob").string() + " --quiet",
                                         300);
    EXPECT_EQ(good.exitCode, 0) << good.out << good.err;
    // In the full repository a self-check renders its expected images from
    // reference/, and its report must not claim shipped golden images.
    const std::string checkHtml = readFile(root / "check_bob" / "index.html");
    EXPECT_NE(checkHtml.find("the reference solution"), std::string::npos);
    EXPECT_EQ(checkHtml.find("shipped golden images"), std::string::npos);
    const CommandResult todo = runVoxlab("check --stage minip --submission " + (root / "class" / "carol").string() +
                                             " --out " + (root / "check_carol").string() + " --quiet",
                                         300);
    EXPECT_EQ(todo.exitCode, 1);
    EXPECT_NE(todo.out.find("minip_ray is not yet implemented"), std::string::npos) << todo.out;
    const CommandResult bad = runVoxlab("grade --submission " + (root / "class" / "bob").string() + " --stage nope");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("unknown stage 'nope'"), std::string::npos) << bad.err;
    // The reference's compiled C++ stages serve the stage runs only: no
    // report folder keeps them (a report may be handed to a student).
    EXPECT_FALSE(fs::exists(root / "reports" / ".expected" / "reference_stages.so"));
    EXPECT_FALSE(fs::exists(root / "check_bob" / ".expected" / "reference_stages.so"));
}

// A student's own tree (voxlab check runs it whole) in which `stage`'s
// files are the reference's, `edit` applied, and every other stage is the
// starter code's (its prerequisites still stubs) except `done`.
fs::path studentTree(const std::string& name, const std::string& stage, const std::vector<std::string>& done,
                     const std::string& find = "", const std::string& replace = "") {
    const fs::path tree = scratch(name) / "assignments";
    fs::copy(kSource / "assignments", tree, fs::copy_options::recursive);
    std::vector<std::string> from = done;
    from.push_back(stage);
    for (const std::string& s : from)
        for (const auto& e : fs::directory_iterator(kSource / "reference" / s))
            if (e.path().extension() == ".glsl" || e.path().extension() == ".cpp")
                fs::copy_file(e.path(), tree / s / e.path().filename(), fs::copy_options::overwrite_existing);
    if (!find.empty()) {
        for (const auto& e : fs::directory_iterator(tree / stage)) {
            std::string text = readFile(e.path());
            const std::size_t at = text.find(find);
            if (at == std::string::npos || e.path().extension() == ".json") continue;
            text.replace(at, find.size(), replace);
            std::ofstream(e.path()) << text;
        }
    }
    return tree;
}

json checkReport(const fs::path& tree, const std::string& stage, CommandResult* result) {
    const fs::path out = tree.parent_path() / "check";
    *result = runVoxlab("check --stage " + stage + " --submission " + tree.string() + " --out " + out.string() +
                            " --quiet",
                        300);
    std::ifstream in(out / "report.json");
    return json::parse(in);
}

// A correct shadows stage in a tree whose gradient stage is still the
// starter code: the scenes the gradient's stub reaches are "blocked by
// gradient/", graded neither for nor against shadows, and the report names
// the stub each reached; the items that ran shadows' own code are graded
// as the stage (before: failed, 1.6 / 10, every shaded scene a checkerboard
// and no word of why).
TEST(Prerequisites, AStubPrerequisiteBlocksScenesInsteadOfFailingTheStage) {
    const fs::path tree = studentTree("blocked_shadows", "shadows", {"sampling", "composite"});
    CommandResult r;
    const json report = checkReport(tree, "shadows", &r);
    const json& shadows = report["stages"].at(0);
    EXPECT_EQ(shadows["status"], "blocked") << shadows["message"];
    EXPECT_NE(r.out.find("blocked by gradient/"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("reached not yet implemented gradient/"), std::string::npos) << r.out;
    EXPECT_FALSE(shadows.contains("hints"));
    int blocked = 0;
    for (const json& scene : shadows["scenes"]) {
        if (scene["status"] == "blocked") {
            ++blocked;
            EXPECT_EQ(scene["max_score"].get<double>(), 0.0);
            EXPECT_EQ(scene["blocked_by"].at(0).get<std::string>().rfind("gradient/", 0), 0u) << scene["blocked_by"];
            EXPECT_NE(scene["message"].get<std::string>().find("blocked by gradient/"), std::string::npos);
        } else {
            EXPECT_EQ(scene["status"], "passed") << scene["name"] << ": " << scene["message"];
            EXPECT_FALSE(scene.contains("not_implemented_reached")) << scene["name"];
        }
    }
    EXPECT_GT(blocked, 0);
    // What ran the stage's own code earns all it can; the blocked part is not counted.
    EXPECT_GT(shadows["max_score"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(shadows["score"].get<double>(), shadows["max_score"].get<double>());
    EXPECT_DOUBLE_EQ(shadows["max_score"].get<double>() + shadows["blocked"]["points"].get<double>(), 4.0 + 6.0);
    const std::string html = readFile(tree.parent_path() / "check" / "index.html");
    EXPECT_NE(html.find("Reached functions not yet implemented"), std::string::npos);
}

// A '>' for the handout's '>=' in marching cubes' case numbers, in a tree
// whose gradient and shading stages are stubs: only the random-cubes check
// tells, and its hint is the one about corners at the isovalue. The shaded
// scenes are blocked, so their failures must not match the signatures of
// edgeCrossing's mistakes (before: three hints, all blaming edgeCrossing).
TEST(Prerequisites, HintsComeOnlyFromItemsThatRanTheStagesOwnCode) {
    const fs::path tree = studentTree("mc_hint", "marching_cubes", {"sampling"}, "if (values[c] >= isovalue)",
                                      "if (values[c] > isovalue)");
    CommandResult r;
    const json report = checkReport(tree, "marching_cubes", &r);
    const json& mc = report["stages"].at(0);
    EXPECT_EQ(mc["status"], "failed") << mc["message"];
    ASSERT_TRUE(mc.contains("hints")) << mc.dump(2).substr(0, 3000);
    ASSERT_EQ(mc["hints"].size(), 1u) << mc["hints"];
    EXPECT_NE(mc["hints"][0].get<std::string>().find("exactly at the isovalue"), std::string::npos) << mc["hints"];
    for (const json& hint : mc["hints"]) EXPECT_EQ(hint.get<std::string>().find("vertex"), std::string::npos) << hint;
    int blocked = 0;
    for (const json& scene : mc["scenes"]) blocked += scene["status"] == "blocked";
    EXPECT_GT(blocked, 0) << "the shaded scenes reach the shading and gradient stubs";
    for (const json& check : mc["checks"]) EXPECT_EQ(check["status"], "failed") << check["name"];
}

// `grade --render-expected DIR` (what a student release ships as expected/)
// leaves the expected outputs alone in DIR: the images and check results of
// the visible scenes and checks, and neither the reference's compiled C++
// stages (the solution, compiled), which the stage runs loaded while
// rendering, nor their work folders.
TEST(GradeCommand, RenderExpectedLeavesOnlyTheExpectedOutputs) {
    const fs::path out = scratch("render_expected") / "expected";
    const CommandResult r = runVoxlab("grade --render-expected " + out.string() + " --stage mip --jobs 1 --quiet", 300);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::vector<std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(out)) files.push_back(fs::relative(e.path(), out).string());
    std::sort(files.begin(), files.end());
    // The record of what was rendered (expected.json: no hidden scenes) and
    // by which GL (gl.txt), beside the outputs.
    std::vector<std::string> want = {"expected.json", "mip", "mip/checks", "mip/gl.txt"};
    const StageManifest mip = loadStageManifest((kSource / "reference").string(), "mip");
    for (const GradedScene& scene : mip.scenes)
        if (!scene.hidden) want.push_back("mip/" + scene.name + ".png");
    for (const GradedCheck& check : mip.checks) want.push_back("mip/checks/" + check.name + ".json");
    std::sort(want.begin(), want.end());
    EXPECT_EQ(files, want);  // no reference_stages.so, no .work, no hidden scene
    std::ifstream record(out / "expected.json");
    EXPECT_FALSE(nlohmann::json::parse(record).value("hidden_scenes", true));
}

}  // namespace
}  // namespace voxlab::testing
