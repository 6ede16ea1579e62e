// Tests for the transfer function: exact evaluation, baked tables (checked
// against an oracle written here, not against evaluate()), and JSON.
#include <gtest/gtest.h>

#include "support/error_of.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "voxlab/error.h"
#include "voxlab/transfer_function.h"

using voxlab::ControlPoint;
using voxlab::TransferFunction;
using voxlab::TransferFunctionTable;
using json = nlohmann::json;

namespace {

// The oracle: the piecewise-linear function straight from the definition,
// by a linear scan over points sorted by value (stable, so a step takes the
// later point at its own value).
std::array<double, 4> oracle(std::vector<ControlPoint> pts, double v) {
    std::stable_sort(pts.begin(), pts.end(),
                     [](const ControlPoint& a, const ControlPoint& b) { return a.value < b.value; });
    auto rgba = [](const ControlPoint& p) {
        return std::array<double, 4>{p.color.r, p.color.g, p.color.b, p.alpha};
    };
    if (v < pts.front().value) return rgba(pts.front());
    size_t i = 0;
    for (size_t k = 0; k < pts.size(); ++k)
        if (pts[k].value <= v) i = k;
    if (i + 1 == pts.size()) return rgba(pts.back());
    const auto a = rgba(pts[i]), b = rgba(pts[i + 1]);
    const double t = (v - pts[i].value) / (pts[i + 1].value - pts[i].value);
    std::array<double, 4> out;
    for (int c = 0; c < 4; ++c) out[c] = a[c] + (b[c] - a[c]) * t;
    return out;
}

double diff(glm::vec4 x, const std::array<double, 4>& y) {
    double d = 0.0;
    for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(double(x[c]) - y[c]));
    return d;
}

// Worst |lookup - oracle| over a dense sweep of [lo, hi] plus every control
// point and its immediate neighbours.
double sweepError(const std::vector<ControlPoint>& pts, const TransferFunctionTable& t) {
    std::vector<double> xs;
    const int n = 200000;
    for (int i = 0; i <= n; ++i) xs.push_back(t.lo + (t.hi - t.lo) * i / n);
    for (const ControlPoint& p : pts) {
        const double eps = 1e-9 * std::max(1.0, std::abs(p.value));
        for (double x : {p.value - eps, p.value, p.value + eps})
            if (x >= t.lo && x <= t.hi) xs.push_back(x);
    }
    double worst = 0.0;
    for (double x : xs) worst = std::max(worst, diff(t.lookup(x), oracle(pts, x)));
    return worst;
}

ControlPoint cp(double v, float r, float g, float b, float a) { return {v, glm::vec3(r, g, b), a}; }

void expectVec(glm::vec4 got, glm::vec4 want) {
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], want[c], 1e-6) << "component " << c;
}

using voxlab::testing::errorOf;

}  // namespace

TEST(TransferFunction, EvaluatesAtPointsAndMidpoints) {
    // Given out of order on purpose: the constructor sorts.
    TransferFunction tf({cp(200, 0, 0, 1, 1), cp(0, 0, 0, 0, 0), cp(100, 1, 0.5f, 0, 0.2f)});
    ASSERT_EQ(tf.points().size(), 3u);
    EXPECT_EQ(tf.points()[0].value, 0);
    EXPECT_EQ(tf.points()[2].value, 200);
    expectVec(tf.evaluate(0), {0, 0, 0, 0});
    expectVec(tf.evaluate(50), {0.5f, 0.25f, 0, 0.1f});
    expectVec(tf.evaluate(100), {1, 0.5f, 0, 0.2f});
    expectVec(tf.evaluate(150), {0.5f, 0.25f, 0.5f, 0.6f});
    expectVec(tf.evaluate(175), {0.25f, 0.125f, 0.75f, 0.8f});
    expectVec(tf.evaluate(200), {0, 0, 1, 1});
}

TEST(TransferFunction, ClampsOutsideAndHandlesTrivialCases) {
    TransferFunction tf({cp(-10, 0.2f, 0.3f, 0.4f, 0.5f), cp(10, 1, 1, 1, 0.9f)});
    expectVec(tf.evaluate(-1e9), {0.2f, 0.3f, 0.4f, 0.5f});
    expectVec(tf.evaluate(1e9), {1, 1, 1, 0.9f});
    expectVec(TransferFunction({cp(3, 0.5f, 0.5f, 0.5f, 0.25f)}).evaluate(-7), {0.5f, 0.5f, 0.5f, 0.25f});
    EXPECT_TRUE(TransferFunction().empty());
    expectVec(TransferFunction().evaluate(1), {0, 0, 0, 0});
}

TEST(TransferFunction, StepTakesTheLaterPoint) {
    // Three points at 10: the stable sort keeps their order, the last wins.
    TransferFunction tf({cp(0, 0, 0, 0, 0), cp(10, 0, 0, 0, 0), cp(10, 0.5f, 0.5f, 0.5f, 0.5f),
                         cp(10, 1, 1, 1, 1), cp(20, 1, 1, 1, 1)});
    EXPECT_NEAR(tf.evaluate(10).a, 1.0, 1e-7);
    EXPECT_NEAR(tf.evaluate(10 - 1e-9).a, 0.0, 1e-7);
    EXPECT_NEAR(tf.evaluate(15).a, 1.0, 1e-7);
    EXPECT_EQ(tf.points()[2].alpha, 0.5f);
}

TEST(TransferFunction, RejectsInvalidPoints) {
    EXPECT_THROW(TransferFunction({cp(0, 1, 1, 1, 1.5f)}), voxlab::Error);
    EXPECT_THROW(TransferFunction({cp(0, -0.1f, 1, 1, 1)}), voxlab::Error);
    EXPECT_THROW(TransferFunction({cp(NAN, 1, 1, 1, 1)}), voxlab::Error);
    EXPECT_THROW(TransferFunction({cp(INFINITY, 1, 1, 1, 1)}), voxlab::Error);
}

TEST(TransferFunction, Ramp) {
    TransferFunction tf = TransferFunction::ramp(100, 300);
    expectVec(tf.evaluate(200), {1, 1, 1, 0.5f});
    expectVec(tf.evaluate(0), {1, 1, 1, 0});
}

// lookup() must be what GL_LINEAR gives for the documented coordinate.
TEST(TransferFunctionTable, LookupMatchesTextureFiltering) {
    TransferFunction tf({cp(3.3, 0, 0.2f, 0, 0), cp(50.7, 1, 0, 0.4f, 0.9f), cp(90, 0, 1, 1, 0.1f)});
    const TransferFunctionTable t = tf.bake(-20, 100, 1.0, 256);
    ASSERT_EQ(t.size, 256);
    for (double v = -30; v <= 110; v += 0.173) {
        const double x = std::clamp((v - t.lo) / (t.hi - t.lo), 0.0, 1.0);
        const double u = x * (t.size - 1) / t.size + 0.5 / t.size;
        const double texel = u * t.size - 0.5;  // GL: texel centres at (i + 0.5) / size
        const int i0 = std::clamp(int(std::floor(texel)), 0, t.size - 1);
        const int i1 = std::min(i0 + 1, t.size - 1);
        const double f = texel - std::floor(texel);
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(t.lookup(v)[c], t.rgba[i0][c] * (1 - f) + t.rgba[i1][c] * f, 1e-6) << v;
    }
}

TEST(TransferFunctionTable, EntriesSampleTheFunction) {
    TransferFunction tf({cp(0, 0, 0, 0, 0), cp(255, 1, 1, 1, 1)});
    const TransferFunctionTable t = tf.bake(0, 255);
    ASSERT_EQ(t.size, 256);
    ASSERT_EQ(t.rgba.size(), 256u);
    EXPECT_NEAR(t.rgba[51].a, 0.2, 1e-6);
    EXPECT_NEAR(t.maxError, 0.0, 1e-6);
}

TEST(TransferFunctionTable, EightBitWithinTolerance) {
    const std::vector<ControlPoint> pts = {cp(0, 0, 0, 0, 0), cp(40, 0, 0, 0, 0), cp(41, 0.2f, 0.6f, 0.1f, 0.3f),
                                           cp(100.5, 0.5f, 0.3f, 0.1f, 0.05f), cp(200, 1, 1, 1, 0.8f),
                                           cp(255, 1, 1, 1, 1)};
    const TransferFunctionTable t = TransferFunction(pts).bake(0, 255);
    EXPECT_LE(t.maxError, 0.5 / 255);
    const double measured = sweepError(pts, t);
    EXPECT_LE(measured, 1.0 / 255);
    EXPECT_LE(measured, t.maxError + 1e-6);  // the bound holds
}

TEST(TransferFunctionTable, TwelveBitSharpRamp) {
    // Alpha 0 -> 1 over one data unit in the middle of 0..4095.
    const std::vector<ControlPoint> pts = {cp(0, 0, 0, 0, 0), cp(2047, 0.1f, 0.1f, 0.1f, 0),
                                           cp(2048, 1, 0.9f, 0.8f, 1), cp(4095, 1, 1, 1, 1)};
    const TransferFunctionTable t = TransferFunction(pts).bake(0, 4095);
    EXPECT_EQ(t.size, 4096);  // one entry per data value
    EXPECT_LE(t.maxError, 0.5 / 255);
    EXPECT_LE(sweepError(pts, t), 1.0 / 255);
}

TEST(TransferFunctionTable, SixteenBitSharpRamp) {
    const std::vector<ControlPoint> pts = {cp(0, 0, 0, 0, 0), cp(32767, 0, 0, 1, 0),
                                           cp(32768, 1, 0, 0, 1), cp(65535, 1, 1, 1, 1)};
    const TransferFunctionTable t = TransferFunction(pts).bake(0, 65535, 0.5 / 255, 65536);
    EXPECT_EQ(t.size, 65536);
    EXPECT_LE(t.maxError, 0.5 / 255);
    EXPECT_LE(sweepError(pts, t), 1.0 / 255);
}

TEST(TransferFunctionTable, TooSmallTableReportsItsErrorHonestly) {
    const std::vector<ControlPoint> pts = {cp(0, 0, 0, 0, 0), cp(32767, 0, 0, 1, 0),
                                           cp(32768, 1, 0, 0, 1), cp(65535, 1, 1, 1, 1)};
    const TransferFunctionTable t = TransferFunction(pts).bake(0, 65535, 0.5 / 255, 16384);
    EXPECT_EQ(t.size, 16384);
    EXPECT_GT(t.maxError, 0.5 / 255);
    const double measured = sweepError(pts, t);
    EXPECT_LE(measured, t.maxError + 1e-6);
    EXPECT_GE(measured, t.maxError - 1e-6);  // attained at a control point
}

TEST(TransferFunctionTable, NonPowerOfTwoMaxSize) {
    const std::vector<ControlPoint> pts = {cp(0, 0, 0, 0, 0), cp(10.25, 1, 1, 1, 1), cp(10.5, 0, 0, 0, 0)};
    const TransferFunctionTable t = TransferFunction(pts).bake(0, 1000, 0.5 / 255, 1000);
    EXPECT_EQ(t.size, 1000);
    EXPECT_NEAR(sweepError(pts, t), t.maxError, 1e-6);
}

TEST(TransferFunctionTable, StepCannotBeBakedAway) {
    const std::vector<ControlPoint> pts = {cp(0, 0, 0, 0, 0), cp(100, 0, 0, 0, 0), cp(100, 1, 1, 1, 0.6f),
                                           cp(200, 1, 1, 1, 0.6f)};
    // On an entry (0..255, size 256: entry 100) the table jumps one entry
    // early, so just below 100 it is off by the whole jump.
    const TransferFunctionTable onEntry = TransferFunction(pts).bake(0, 255, 0.5 / 255, 256);
    EXPECT_NEAR(onEntry.maxError, 1.0, 1e-6);
    // Halfway between entries it is off by half the jump on either side.
    const TransferFunctionTable between = TransferFunction(pts).bake(0, 200);
    EXPECT_EQ(between.size, 1 << 20);  // the default maxSize: a step never converges
    EXPECT_NEAR(between.maxError, 0.5, 1e-3);
    for (const TransferFunctionTable* t : {&onEntry, &between})
        EXPECT_NEAR(sweepError(pts, *t), t->maxError, 1e-3);
}

// Random functions and ranges: the reported bound must never be beaten by
// the measured error (within float rounding), and must be reached.
TEST(TransferFunctionTable, ReportedErrorIsTheTrueMaximum) {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> value(-1000, 3000);
    std::uniform_real_distribution<float> unit(0, 1);
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<ControlPoint> pts;
        for (int k = 0; k < 6; ++k) pts.push_back(cp(value(rng), unit(rng), unit(rng), unit(rng), unit(rng)));
        const TransferFunctionTable t = TransferFunction(pts).bake(0, 2000, 0.5 / 255, 2048);
        const double measured = sweepError(pts, t);
        EXPECT_LE(measured, t.maxError + 1e-5) << "trial " << trial;
        EXPECT_GE(measured, t.maxError - 1e-5) << "trial " << trial;
        if (t.maxError <= 0.5 / 255) EXPECT_LE(measured, 1.0 / 255);
    }
}

TEST(TransferFunctionTable, DegenerateRange) {
    TransferFunction tf({cp(0, 0, 0, 0, 0), cp(10, 1, 1, 1, 1)});
    const TransferFunctionTable t = tf.bake(5, 5);
    EXPECT_EQ(t.size, 2);
    EXPECT_GT(t.hi, t.lo);
    expectVec(t.lookup(5), tf.evaluate(5));
    expectVec(t.lookup(-100), tf.evaluate(5));
    expectVec(t.lookup(100), tf.evaluate(5));
}

TEST(TransferFunctionJson, ParsesBothForms) {
    const json arr = json::parse(R"([{"value": 10, "color": [1, 0.5, 0], "alpha": 0.25},
                                     {"value": 0, "color": [0, 0, 0], "alpha": 0}])");
    TransferFunction a = TransferFunction::fromJson(arr, "tf.json");
    ASSERT_EQ(a.points().size(), 2u);
    EXPECT_EQ(a.points()[1].value, 10);
    EXPECT_EQ(a.points()[1].color.g, 0.5f);
    const json obj = {{"name", "x"}, {"description", "y"}, {"points", arr}};
    EXPECT_EQ(TransferFunction::fromJson(obj, "tf.json").points().size(), 2u);
}

TEST(TransferFunctionJson, ErrorsNameTheLocation) {
    struct Case {
        const char* text;
        const char* message;
    };
    const Case cases[] = {
        {R"([{"value":0,"color":[0,0,0],"alpha":0},{"value":1,"color":[0,0,0],"alpha":0},
            {"value":2,"color":[0,0],"alpha":0}])",
         "tf.json: points[2].color: expected an array of 3 numbers in 0..1"},
        {R"([{"value":0,"color":[0,0,0],"alpha":0,"opacity":1}])", "tf.json: points[0]: unknown key 'opacity'"},
        {R"([{"value":0,"color":[0,0,0]}])", "tf.json: points[0]: missing key 'alpha'"},
        {R"([{"value":"0","color":[0,0,0],"alpha":0}])", "tf.json: points[0].value: expected a number"},
        {R"([{"value":0,"color":[0,0,2],"alpha":0}])", "tf.json: points[0].color: expected"},
        {R"([{"value":0,"color":[0,"a",0],"alpha":0}])", "tf.json: points[0].color: expected"},
        {R"([{"value":0,"color":[0,0,0],"alpha":1.5}])", "tf.json: points[0].alpha: expected a number in 0..1"},
        {R"([{"value":0,"color":[0,0,0],"alpha":true}])", "tf.json: points[0].alpha: expected"},
        {R"([3])", "tf.json: points[0]: expected an object"},
        {R"([])", "tf.json: points: expected at least 1 control point"},
        {R"({"points": []})", "tf.json: points: expected at least 1"},
        {R"({"points": 3})", "tf.json: points: expected an array"},
        {R"({"name": "a"})", "tf.json: missing key 'points'"},
        {R"({"points": [], "colour": 1})", "tf.json: unknown key 'colour'"},
        {R"({"points": [], "name": 1})", "tf.json: name: expected a string"},
        {R"(42)", "tf.json: expected an array of control points"},
    };
    for (const Case& c : cases) {
        const std::string msg = errorOf([&] { TransferFunction::fromJson(json::parse(c.text), "tf.json"); });
        EXPECT_NE(msg.find(c.message), std::string::npos) << "got: '" << msg << "' for " << c.text;
    }
    // Under a scene key.
    const std::string msg = errorOf([] {
        TransferFunction::fromJson(json::parse(R"([{"value":0,"color":[0,0,0],"alpha":0},{"value":1}])"),
                                   "scene.json", "transfer_function");
    });
    EXPECT_EQ(msg, "scene.json: transfer_function[1]: missing key 'color'");
}

TEST(TransferFunctionJson, RoundTripsExactly) {
    TransferFunction tf({cp(-5.25, 0.1f, 0.2f, 0.3f, 0.7f), cp(1e4, 1, 0.333f, 0, 0.05f), cp(1e4, 0, 0, 1, 1)});
    const json j = tf.toJson();
    EXPECT_EQ(j[0]["color"][0].dump(), "0.1");  // shortest form, not 0.10000000149011612
    const TransferFunction back = TransferFunction::fromJson(json::parse(j.dump()), "x");
    ASSERT_EQ(back.points().size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(back.points()[i].value, tf.points()[i].value);
        EXPECT_EQ(back.points()[i].color, tf.points()[i].color);
        EXPECT_EQ(back.points()[i].alpha, tf.points()[i].alpha);
    }
}

TEST(TransferFunctionJson, LoadReportsFileErrorsOnOneLine) {
    const std::string dir = std::filesystem::temp_directory_path() / ("voxlab_tf_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string good = dir + "/good.json", bad = dir + "/bad.json", missing = dir + "/none.json";
    std::ofstream(good) << R"({"name": "g", "points": [{"value": 1, "color": [1, 1, 1], "alpha": 0.5}]})";
    std::ofstream(bad) << "[\n  {\"value\": 1,\n   \"color\": [1, 1, 1],,\n  }\n]\n";
    EXPECT_EQ(TransferFunction::load(good).points().size(), 1u);
    for (const std::string& path : {bad, missing}) {
        const std::string msg = errorOf([&] { TransferFunction::load(path); });
        EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
    EXPECT_NE(errorOf([&] { TransferFunction::load(bad); }).find("line 3"), std::string::npos);
    std::filesystem::remove_all(dir);
}

// The presets shipped in datasets/tf/ all load and stay simple.
TEST(TransferFunctionPresets, AllLoad) {
    const std::filesystem::path dir = std::filesystem::path(VOXLAB_SOURCE_DIR) / "datasets" / "tf";
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().string());
        const TransferFunction tf = TransferFunction::load(entry.path().string());
        EXPECT_GE(tf.points().size(), 3u);
        EXPECT_LE(tf.points().size(), 6u);
        EXPECT_EQ(tf.points().front().alpha, 0.0f);  // the background stays clear
        ++count;
    }
    EXPECT_EQ(count, 9);
}
