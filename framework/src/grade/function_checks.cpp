// voxlab: function-level checks for the grader (see function_checks.h). Each
// stage's checks live in its folder, framework/stages/STAGE/check.cpp; what
// they share is voxlab/function_check_support.h. Here: the list of them, and
// the comparison of a submission's results with the expected ones.
#include "voxlab/function_checks.h"

#include <cstdio>
#include <filesystem>
#include <map>

#include "voxlab/error.h"
#include "voxlab/function_check_support.h"
#include "voxlab/project_root.h"

#define VOXLAB_STAGE_CHECKS(stage) void stageChecks_##stage(check::StageChecks& checks);
namespace voxlab {
#include "voxlab_stage_checks.inc"
}  // namespace voxlab
#undef VOXLAB_STAGE_CHECKS

namespace voxlab {
namespace {

using namespace check;

// Every stage's checks, in the stages' order (framework/stages/stages.cmake).
const std::vector<CheckDefinition>& definitions() {
    static const std::vector<CheckDefinition> list = [] {
        std::vector<CheckDefinition> all;
#define VOXLAB_STAGE_CHECKS(stage)                \
    {                                             \
        StageChecks checks(#stage, &all);         \
        stageChecks_##stage(checks);              \
    }
#include "voxlab_stage_checks.inc"
#undef VOXLAB_STAGE_CHECKS
        return all;
    }();
    return list;
}

std::string checkedRoot(const std::string& implementationRoot) {
    if (implementationRoot.empty()) return projectRoot() + "/reference";
    if (!std::filesystem::is_directory(implementationRoot))
        throw Error("implementation root '" + implementationRoot + "' is not a folder");
    return implementationRoot;
}

const CheckDefinition& definition(const std::string& name) {
    for (const CheckDefinition& d : definitions())
        if (d.info.name == name) return d;
    std::string known;
    for (const CheckDefinition& d : definitions()) known += (known.empty() ? "" : ", ") + d.info.name;
    throw Error("unknown function check '" + name + "' (known: " + known + ")");
}

// A short, readable form of inputs and outputs for the examples.
std::string brief(const json& j) {
    if (j.is_null()) return "NaN";
    if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
    if (j.is_number_integer()) return std::to_string(j.get<long long>());
    if (j.is_number()) {
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", j.get<double>());
        return text;
    }
    if (j.is_string()) return j.get<std::string>();
    std::string out;
    if (j.is_array()) {
        for (const json& item : j) out += (out.empty() ? "" : ", ") + brief(item);
        return "[" + out + "]";
    }
    for (const auto& item : j.items()) out += (out.empty() ? "" : ", ") + item.key() + " " + brief(item.value());
    return "{" + out + "}";
}

std::string formatDelta(double delta) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", delta);
    return text;
}

// What a student needs to rebuild a check's inputs: the seed, the random
// volume's dimensions, spacing and value mapping, and the units of it all.
json reproduction(const json& expected) {
    json out = json::object();
    if (expected.contains("seed") && expected["seed"].is_number_unsigned()) {
        char seed[16];
        std::snprintf(seed, sizeof seed, "0x%08X", expected["seed"].get<unsigned>());
        out["seed"] = seed;
    }
    const json volume = expected.value("fixture", json::object()).value("volume", json());
    if (!volume.is_object() || !volume.contains("dims") || !volume.contains("extent")) return out;
    const glm::dvec3 dims = vecOf(volume["dims"]), extent = vecOf(volume["extent"]);
    const glm::dvec3 spacing = extent / dims;
    const double offset = volume.value("value_offset", 0.0);
    char values[96];
    std::snprintf(values, sizeof values, "data value = stored value x %g %c %g", volume.value("value_scale", 1.0),
                  offset < 0 ? '-' : '+', std::abs(offset));
    const auto tidy = [](glm::dvec3 v) {  // floats as people write them: 1.3, not 1.3000000715
        return json::array({std::round(v.x * 1e6) / 1e6, std::round(v.y * 1e6) / 1e6, std::round(v.z * 1e6) / 1e6});
    };
    out["volume"] = {
        {"dims", volume["dims"]}, {"spacing", tidy(spacing)}, {"extent", tidy(extent)}, {"values", values}};
    out["units"] = "world units for points, origins, t, steps and extents (the volume's box is [0, extent] on "
                   "each axis, extent = dims x spacing, voxel (i, j, k) centred at (i+1/2, j+1/2, k+1/2) x "
                   "spacing); data units for values, thresholds and isovalues";
    return out;
}

}  // namespace

const std::vector<FunctionCheckInfo>& functionChecks() {
    static const std::vector<FunctionCheckInfo> infos = [] {
        std::vector<FunctionCheckInfo> list;
        for (const CheckDefinition& d : definitions()) list.push_back(d.info);
        return list;
    }();
    return infos;
}

json runFunctionCheck(const std::string& name, const std::string& implementationRoot) {
    const CheckDefinition& check = definition(name);
    return check.run(checkedRoot(implementationRoot));
}

CheckComparison compareFunctionCheck(const std::string& name, const json& expected, const json& actual) {
    const CheckDefinition& check = definition(name);
    const std::string where = "function check " + name + ": ";
    for (const json* j : {&expected, &actual}) {
        if (!j->is_object() || !j->contains("cases") || !(*j)["cases"].is_array())
            throw Error(where + "expected an object with a list of cases");
        if (j->value("check", std::string()) != name)
            throw Error(where + "the results are those of check '" + j->value("check", std::string("?")) + "'");
    }
    const json& expectedCases = expected["cases"];
    const json& actualCases = actual["cases"];
    const bool sameFixture = expected.value("fixture", json()) == actual.value("fixture", json());
    if (expectedCases.size() != actualCases.size() || !sameFixture)
        throw Error(where + "the expected and actual results were made from different inputs");

    CheckComparison result;
    result.cases = int(expectedCases.size());
    try {
        result.inputs = reproduction(expected);
    } catch (const json::exception&) {  // a fixture of another shape: nothing to say
    }
    double worst = 0.0, worstPassing = 0.0;
    std::map<std::string, std::pair<int, int>> perFunction;  // failed, cases
    for (std::size_t i = 0; i < expectedCases.size(); ++i) {
        const json& e = expectedCases[i];
        const json& a = actualCases[i];
        const std::string function = e.at("function").get<std::string>();
        const bool sameCase = a.is_object() && a.value("function", std::string()) == function &&
                              a.value("input", json()) == e.at("input");
        if (!sameCase)
            throw Error(where + "the expected and actual results were made from different inputs (case " +
                        std::to_string(i) + ")");
        const json& got = a.value("output", json());
        CaseVerdict verdict;
        if (got.is_object() && got.contains("error"))
            verdict = failure("threw: " + got["error"].get<std::string>());
        else
            verdict = check.compare(function, e["input"], e.at("output"), got);
        std::pair<int, int>& counts = perFunction[function];
        ++counts.second;
        if (verdict.pass) {
            worstPassing = std::max(worstPassing, verdict.delta);
            continue;
        }
        ++counts.first;
        ++result.failed;
        if (!std::isnan(verdict.delta)) worst = std::max(worst, verdict.delta);
        if (result.examples.size() < 3)
            result.examples.push_back(function + ", case " + std::to_string(i) + ": input " + brief(e["input"]) +
                                      "; expected " + brief(e["output"]) + "; got " + brief(got) +
                                      (verdict.note.empty() ? "" : " (" + verdict.note + ")"));
    }
    if (result.failed == 0) {
        result.summary = "all " + std::to_string(result.cases) + " cases agree";
        if (worstPassing > 0.0) result.summary += " (worst |\u0394| " + formatDelta(worstPassing) + ")";
        return result;
    }
    result.summary = std::to_string(result.failed) + " of " + std::to_string(result.cases) + " cases differ";
    if (perFunction.size() > 1) {
        std::string parts;
        for (const auto& [function, counts] : perFunction)
            if (counts.first > 0)
                parts += (parts.empty() ? "" : ", ") + function + " " + std::to_string(counts.first) + " of " +
                         std::to_string(counts.second);
        result.summary += " (" + parts + ")";
    }
    if (worst > 0.0) result.summary += "; worst |\u0394| " + formatDelta(worst);
    return result;
}

}  // namespace voxlab
