// voxlab: a course's assignment file, and what students actually upload.
//
// An assignment file (courses/*.json; format in docs/grading.md) chooses
// which stages one assignment grades and how many points each is worth,
// how visible each test is on Gradescope, and what a late submission
// costs. `voxlab grade`, `voxlab check` (--assignment FILE) and the
// Gradescope script read it, so choosing stages never means editing a
// script:
//
//   {"title": "Assignment 1: rays",
//    "stages": [{"stage": "sampling", "points": 20},
//               {"stage": "mip", "points": 30,
//                "visibility": {"ct_signed_air": "hidden"}}],
//    "visibility": "visible",
//    "hidden_scenes": "after_due_date",
//    "due": "2026-12-01T23:59:00+01:00",
//    "late": {"penalty_per_day": 0.1, "max_days": 3}}
//
// Visibility is Gradescope's: "visible", "hidden" (the instructor's only)
// or "after_due_date". A test gets, in this order, its stage's per-item
// value, its stage's value, "hidden_scenes" for a scene its manifest marks
// hidden, or the file's "visibility".
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace voxlab {

struct AssignmentStage {
    std::string stage;
    std::optional<double> points;                   // default: the manifest's
    std::string visibility;                         // empty: the file's default
    std::map<std::string, std::string> items;       // scene or check name -> visibility
};

struct Assignment {
    std::string path;
    std::string title;
    std::vector<AssignmentStage> stages;
    std::string visibility = "visible";
    std::string hiddenScenes = "after_due_date";
    std::optional<double> due;  // seconds since 1970-01-01 UTC
    double penaltyPerDay = 0.0; // fraction of the score per day (or part of one) late
    std::optional<double> maxDaysLate;  // later than this: no points
};

// Reads and checks an assignment file against the stages under
// `referenceRoot`. Every mistake (unknown stage or key, a visibility that
// is not one of the three, points below 0, a bad date) is an Error naming
// the file and the entry.
Assignment loadAssignment(const std::string& path, const std::string& referenceRoot);

// Seconds since 1970-01-01 UTC of an ISO 8601 time such as
// 2026-12-01T23:59:00Z, 2026-12-01T23:59:00.123456-08:00 or 2026-12-01
// (midnight UTC); nullopt when `text` is not one.
std::optional<double> parseIsoTime(const std::string& text);

// Applies the assignment to a graded report: each scene and check gets its
// "visibility", and a submission after the due date loses the late
// penalty (report "late": days, factor; "score" scaled, "score_on_time"
// kept). `due` overrides the file's due date (Gradescope's metadata).
void applyAssignment(nlohmann::json& report, const Assignment& assignment, std::optional<double> submittedAt,
                     std::optional<double> due = std::nullopt);

// Where an upload keeps its stage folders. Students upload the assignments/
// folder itself, its contents, a release folder with assignments/ nested
// inside, or loose stage files. Returns the folder that holds the most
// stage folders (the upload itself, or one below it, up to 6 levels, never
// through a symbolic link); when no stage folder exists anywhere, the loose
// files named in the stages' manifests are copied into `staging/<stage>/`
// and `staging` is returned. `note` says what was done ("" when the upload
// was already in shape).
std::string submissionRoot(const std::string& upload, const std::string& referenceRoot,
                           const std::vector<std::string>& stages, const std::string& staging,
                           std::string* note);

}  // namespace voxlab
