// voxlab: similar stage code across a class, as evidence for a human.
//
// `voxlab grade --batch` compares every pair of submissions stage by stage
// and lists the pairs whose code is suspiciously alike (OUT/similarity.json
// and OUT/similarity.html), MOSS-style: the score and the matching regions
// side by side. It never decides anything and changes no grade. Similar code
// has innocent causes (a stage with one natural way to write it, code from
// the handout or the lecture, students who were allowed to work together);
// a person reads the evidence and decides.
//
// How code is compared (the reasoning is at the top of similarity.cpp):
//   - each file is cut into tokens; comments, whitespace, braces and
//     preprocessor lines are dropped, every identifier that is not a GLSL or
//     C++ keyword, type or called builtin becomes one token class, and
//     numbers are kept by value (1.0, 1., 1.0f and 1e0 are the same token);
//   - every run of k consecutive tokens (a k-gram) is hashed, and winnowing
//     keeps the smallest hash of every w consecutive ones as a fingerprint;
//   - fingerprints that occur anywhere in the stage's starter code are
//     dropped (every student starts from it), and so are those found in more
//     than `commonLimit` submissions (an idiom the whole class writes);
//   - the score of a pair is shared fingerprints / min(fingerprints of
//     either): 1 when everything one of them wrote is also in the other.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace voxlab {

struct SimilarityOptions {
    // A pair is flagged when its score is at least `threshold` and at least
    // minMatchedTokens of each side's tokens lie in matching code. Measured
    // (similarity.cpp): disguised copies score 0.81 to 1, independent
    // solutions at most 0.36; the obvious 5-line MIP loop shares 26 tokens.
    double threshold = 0.5;
    int minMatchedTokens = 30;
    int kgram = 8;                // k: tokens per hashed k-gram (the noise threshold)
    int window = 4;               // w: winnowing window, in k-grams
    int commonLimit = 10;         // fingerprints in more submissions than this are ignored
    std::size_t maxFileBytes = std::size_t(1) << 20;  // larger files are not read (the grader's cap)
};

// One token of a source file: its normalised text and its 1-based line.
struct SourceToken {
    std::string text;
    int line = 0;
};

// The tokens of a GLSL or C++ source, normalised as described above. Never
// throws on any bytes: an unterminated comment or string ends at the end of
// the text, a byte that is no part of the languages is skipped.
std::vector<SourceToken> tokenizeSource(std::string_view text);

struct SimilaritySubmission {
    std::string name;    // shown in the report
    std::string folder;  // shaped like assignments/ (<folder>/<stage>/<file>)
};

struct SimilarityStage {
    std::string stage;               // its folder name
    std::vector<std::string> files;  // the files students write, by name (the manifest's "files")
};

// The code of one submission in one stage, as read.
struct StageCode {
    std::vector<std::string> files;  // "<stage>/<file>", the same order as the stage's files
    std::vector<std::string> texts;  // their contents ("" when not read)
    std::vector<std::string> problems;  // why a file was not read ("" when it was)
};

// A matching region: lines [first, last] of file `file` (an index into
// StageCode::files) in each of the two submissions.
struct MatchedRegion {
    int fileA = 0, firstA = 0, lastA = 0;
    int fileB = 0, firstB = 0, lastB = 0;
    int tokens = 0;  // length of the match in A, in tokens
};

struct SimilarPair {
    std::string stage;
    std::size_t a = 0, b = 0;  // indices into the submissions, a < b
    double score = 0.0;        // shared / min(fingerprintsA, fingerprintsB)
    int shared = 0, fingerprintsA = 0, fingerprintsB = 0;
    int matchedTokensA = 0, matchedTokensB = 0;  // tokens covered by shared fingerprints' k-grams
    std::vector<MatchedRegion> regions;          // in A's order
};

struct SimilarityReport {
    SimilarityOptions options;
    std::vector<std::string> names;   // the submissions, in order
    std::vector<std::string> stages;  // the stages compared
    std::vector<std::vector<StageCode>> code;  // [stage][submission]
    std::vector<SimilarPair> pairs;   // flagged pairs, highest score first
    std::size_t pairsCompared = 0;    // pairs in which both had code of their own in the stage
    std::vector<std::string> notes;   // files not read and why, stages without starter code
};

// Compares the submissions stage by stage. The starter code of a stage is
// read from `starterRoot/<stage>/<file>` (the project's assignments/); a
// stage without it is compared as it is, and a note says so. A file that is
// missing, a link, not a regular file, larger than maxFileBytes or binary
// (it holds a NUL byte) is left out, with a note. Throws nothing for
// anything a submission holds.
SimilarityReport findSimilarCode(const std::vector<SimilaritySubmission>& submissions,
                                 const std::vector<SimilarityStage>& stages, const std::string& starterRoot,
                                 const SimilarityOptions& options);

// The stages' files from their manifests under referenceRoot (grading.h):
// `stages` empty means every graded stage.
std::vector<SimilarityStage> similarityStages(const std::string& referenceRoot,
                                              const std::vector<std::string>& stages);

// The report for scripts (no file contents), and the standalone page: per
// flagged pair the stage, the names, the score and both files side by side
// with the matching regions highlighted.
nlohmann::json similarityJson(const SimilarityReport& report);
std::string similarityHtml(const SimilarityReport& report);

// Writes DIR/similarity.json and DIR/similarity.html (atomically).
void writeSimilarityReport(const SimilarityReport& report, const std::string& dir);

// --similarity-threshold: a number in (0, 1], or "off" (nullopt). Anything
// else is an Error naming the option.
std::optional<double> parseSimilarityThreshold(const std::string& text);

}  // namespace voxlab
