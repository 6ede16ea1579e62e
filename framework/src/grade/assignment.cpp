// voxlab: assignment files and upload layouts (assignment.h).
//
// Dates: Gradescope's metadata writes times like
// 2026-12-01T23:59:00.000000-08:00, and instructors write 2026-12-01T23:59Z
// or a plain date. Days are counted from the civil calendar with the
// proleptic Gregorian rule (days_from_civil, H. Hinnant's derivation), so no
// time-zone database is needed: the offset is in the text.
#include "voxlab/assignment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "voxlab/error.h"
#include "voxlab/grading.h"

namespace voxlab {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

long long daysFromCivil(long long y, unsigned m, unsigned d) {
    y -= m <= 2;
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const unsigned yoe = unsigned(y - era * 400);
    const unsigned doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
    const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + (long long)doe - 719468;
}

// Reads `count` digits at `at`; false if any is not a digit.
bool digits(const std::string& s, std::size_t at, int count, int* value) {
    if (at + count > s.size()) return false;
    *value = 0;
    for (int i = 0; i < count; ++i) {
        const char c = s[at + i];
        if (c < '0' || c > '9') return false;
        *value = *value * 10 + (c - '0');
    }
    return true;
}

const std::set<std::string> kVisibilities = {"visible", "hidden", "after_due_date"};

std::string visibilityOf(const json& value, const std::string& where) {
    if (!value.is_string() || !kVisibilities.count(value.get<std::string>()))
        throw Error(where + ": visibility must be \"visible\", \"hidden\" or \"after_due_date\"");
    return value.get<std::string>();
}

void rejectUnknownKeys(const json& object, const std::set<std::string>& known, const std::string& where) {
    for (const auto& [key, value] : object.items())
        if (!known.count(key)) throw Error(where + ": unknown key \"" + key + "\"");
}

AssignmentStage stageEntry(const json& entry, const std::string& where, const std::string& referenceRoot) {
    if (!entry.is_object() || !entry.contains("stage") || !entry["stage"].is_string())
        throw Error(where + ": each stage is an object with a \"stage\" name");
    rejectUnknownKeys(entry, {"stage", "points", "visibility"}, where);
    AssignmentStage s;
    s.stage = entry["stage"];
    const std::string at = where + " (" + s.stage + ")";
    if (!fs::exists(fs::path(referenceRoot) / s.stage / "grading.json"))
        throw Error(at + ": unknown stage (no " + referenceRoot + "/" + s.stage + "/grading.json)");
    if (entry.contains("points")) {
        if (!entry["points"].is_number() || !(entry["points"].get<double>() >= 0.0) ||
            !(entry["points"].get<double>() <= 1e6))
            throw Error(at + ": points must be a number in 0..1000000");
        s.points = entry["points"].get<double>();
    }
    if (!entry.contains("visibility")) return s;
    if (!entry["visibility"].is_object()) {
        s.visibility = visibilityOf(entry["visibility"], at);
        return s;
    }
    const StageManifest manifest = loadStageManifest(referenceRoot, s.stage);
    std::set<std::string> names;
    for (const GradedScene& scene : manifest.scenes) names.insert(scene.name);
    for (const GradedCheck& check : manifest.checks) names.insert(check.name);
    for (const auto& [name, value] : entry["visibility"].items()) {
        if (!names.count(name)) throw Error(at + ": visibility names \"" + name + "\", which is no scene or check of the stage");
        s.items[name] = visibilityOf(value, at + " " + name);
    }
    return s;
}

double requireTime(const json& value, const std::string& where) {
    const std::optional<double> t = value.is_string() ? parseIsoTime(value.get<std::string>()) : std::nullopt;
    if (!t) throw Error(where + ": not an ISO 8601 time (e.g. 2026-12-01T23:59:00+01:00)");
    return *t;
}

void readLatePolicy(const json& late, Assignment& a) {
    const std::string where = a.path + ": late";
    if (!late.is_object()) throw Error(where + ": must be an object");
    rejectUnknownKeys(late, {"penalty_per_day", "max_days"}, where);
    if (late.contains("penalty_per_day")) {
        const json& p = late["penalty_per_day"];
        if (!p.is_number() || !(p.get<double>() >= 0.0 && p.get<double>() <= 1.0))
            throw Error(where + ": penalty_per_day must be a fraction in 0..1");
        a.penaltyPerDay = p;
    }
    if (late.contains("max_days")) {
        const json& d = late["max_days"];
        if (!d.is_number() || !(d.get<double>() >= 0.0 && d.get<double>() <= 3650.0))
            throw Error(where + ": max_days must be a number of days in 0..3650");
        a.maxDaysLate = d.get<double>();
    }
}

}  // namespace

std::optional<double> parseIsoTime(const std::string& s) {
    int y, mo, d, h = 0, mi = 0, sec = 0;
    if (!digits(s, 0, 4, &y) || s.size() < 10 || s[4] != '-' || !digits(s, 5, 2, &mo) || s[7] != '-' ||
        !digits(s, 8, 2, &d))
        return std::nullopt;
    static const int kDays[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (mo < 1 || mo > 12 || d < 1 || d > kDays[mo - 1]) return std::nullopt;
    std::size_t at = 10;
    double fraction = 0.0, offset = 0.0;
    if (at < s.size() && (s[at] == 'T' || s[at] == ' ')) {
        if (!digits(s, at + 1, 2, &h) || at + 3 >= s.size() || s[at + 3] != ':' || !digits(s, at + 4, 2, &mi))
            return std::nullopt;
        at += 6;
        if (at < s.size() && s[at] == ':') {
            if (!digits(s, at + 1, 2, &sec)) return std::nullopt;
            at += 3;
            if (at < s.size() && s[at] == '.') {
                double scale = 0.1;
                for (++at; at < s.size() && s[at] >= '0' && s[at] <= '9' && scale > 1e-12; ++at, scale /= 10)
                    fraction += (s[at] - '0') * scale;
            }
        }
        if (h > 23 || mi > 59 || sec > 60) return std::nullopt;
        if (at < s.size() && s[at] == 'Z') {
            ++at;
        } else if (at < s.size() && (s[at] == '+' || s[at] == '-')) {
            int oh, om;
            if (!digits(s, at + 1, 2, &oh) || at + 3 >= s.size() || s[at + 3] != ':' || !digits(s, at + 4, 2, &om) ||
                oh > 23 || om > 59)
                return std::nullopt;
            offset = (s[at] == '+' ? 1.0 : -1.0) * (oh * 3600.0 + om * 60.0);
            at += 6;
        }
    }
    if (at != s.size()) return std::nullopt;
    return double(daysFromCivil(y, unsigned(mo), unsigned(d))) * 86400.0 + h * 3600.0 + mi * 60.0 + sec + fraction -
           offset;
}

Assignment loadAssignment(const std::string& path, const std::string& referenceRoot) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot read the assignment file");
    json j = json::parse(in, nullptr, false);
    if (j.is_discarded() || !j.is_object()) throw Error(path + ": not a JSON object");
    Assignment a;
    a.path = path;
    rejectUnknownKeys(j, {"title", "stages", "visibility", "hidden_scenes", "due", "late"}, path);
    if (j.contains("title")) {
        if (!j["title"].is_string()) throw Error(path + ": title must be a string");
        a.title = j["title"];
    }
    if (!j.contains("stages") || !j["stages"].is_array() || j["stages"].empty())
        throw Error(path + ": \"stages\" must be a non-empty list");
    std::set<std::string> seen;
    for (std::size_t i = 0; i < j["stages"].size(); ++i) {
        AssignmentStage s = stageEntry(j["stages"][i], path + ": stages[" + std::to_string(i) + "]", referenceRoot);
        if (!seen.insert(s.stage).second) throw Error(path + ": stage " + s.stage + " is listed twice");
        a.stages.push_back(std::move(s));
    }
    if (j.contains("visibility")) a.visibility = visibilityOf(j["visibility"], path + ": visibility");
    if (j.contains("hidden_scenes")) a.hiddenScenes = visibilityOf(j["hidden_scenes"], path + ": hidden_scenes");
    if (j.contains("due")) a.due = requireTime(j["due"], path + ": due");
    if (j.contains("late")) readLatePolicy(j["late"], a);
    return a;
}

void applyAssignment(json& report, const Assignment& a, std::optional<double> submittedAt, std::optional<double> due) {
    for (json& stage : report["stages"]) {
        const std::string name = stage.value("stage", "");
        const auto it = std::find_if(a.stages.begin(), a.stages.end(),
                                     [&](const AssignmentStage& s) { return s.stage == name; });
        for (const char* kind : {"scenes", "checks"})
            for (json& item : stage[kind]) {
                std::string v = a.visibility;
                if (item.value("hidden", false)) v = a.hiddenScenes;
                if (it != a.stages.end() && !it->visibility.empty()) v = it->visibility;
                if (it != a.stages.end() && it->items.count(item.value("name", "")))
                    v = it->items.at(item.value("name", ""));
                item["visibility"] = v;
            }
    }
    if (!due) due = a.due;
    if (!due || !submittedAt || *submittedAt <= *due) return;
    const double days = std::ceil((*submittedAt - *due) / 86400.0);
    const bool tooLate = a.maxDaysLate && days > *a.maxDaysLate;
    const double factor = tooLate ? 0.0 : std::max(0.0, 1.0 - a.penaltyPerDay * days);
    report["score_on_time"] = report.value("score", 0.0);
    report["score"] = report.value("score", 0.0) * factor;
    char message[160];
    std::snprintf(message, sizeof message, "submitted %g day%s late: %s", days, days == 1 ? "" : "s",
                  tooLate ? "past the last day accepted, no points" : "");
    std::string text = message;
    if (!tooLate) {
        std::snprintf(message, sizeof message, "score times %.2f", factor);
        text += message;
    }
    report["late"] = {{"days", days}, {"factor", factor}, {"message", text}};
}

std::string submissionRoot(const std::string& upload, const std::string& referenceRoot,
                           const std::vector<std::string>& stages, const std::string& staging, std::string* note) {
    note->clear();
    std::map<std::string, std::vector<std::string>> files;  // stage -> its files' names
    for (const std::string& s : stages) files[s] = loadStageManifest(referenceRoot, s).files;
    const auto holds = [&](const fs::path& dir) {  // how many stage folders with a stage file
        int n = 0;
        for (const auto& [stage, names] : files) {
            std::error_code ec;
            for (const std::string& f : names)
                if (fs::is_regular_file(dir / stage / f, ec)) {
                    ++n;
                    break;
                }
        }
        return n;
    };
    // Breadth first, so that of equal candidates the shallowest wins.
    fs::path best = upload;
    int bestCount = holds(upload);
    std::vector<fs::path> level = {upload};
    std::map<std::string, fs::path> loose;  // file name -> the shallowest file with it
    std::size_t visited = 0;
    for (int depth = 0; depth < 6 && !level.empty() && visited < 20000; ++depth) {
        std::vector<fs::path> next;
        for (const fs::path& dir : level) {
            std::error_code ec;
            for (fs::directory_iterator it(dir, ec), end; !ec && it != end && visited < 20000; it.increment(ec)) {
                ++visited;
                const fs::path p = it->path();
                if (it->is_symlink(ec)) continue;
                if (it->is_directory(ec)) {
                    next.push_back(p);
                    const int n = holds(p);
                    if (n > bestCount) best = p, bestCount = n;
                } else if (it->is_regular_file(ec) && !loose.count(p.filename().string())) {
                    loose[p.filename().string()] = p;
                }
            }
        }
        std::sort(next.begin(), next.end());
        level = std::move(next);
    }
    if (bestCount > 0) {
        if (best != fs::path(upload))
            *note = "graded the stage folders found in " + fs::relative(best, upload).string() + "/";
        return best.string();
    }
    std::string placed;
    for (const auto& [stage, names] : files)
        for (const std::string& f : names)
            if (loose.count(f) && fs::file_size(loose[f]) <= (std::size_t(16) << 20)) {
                fs::create_directories(fs::path(staging) / stage);
                fs::copy_file(loose[f], fs::path(staging) / stage / f, fs::copy_options::overwrite_existing);
                placed += (placed.empty() ? "" : ", ") + fs::relative(loose[f], upload).string() + " -> " + stage + "/";
            }
    if (placed.empty()) return upload;
    *note = "loose files placed in their stage folders: " + placed;
    return staging;
}

}  // namespace voxlab
