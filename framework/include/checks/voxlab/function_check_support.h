// voxlab: what the stages' function checks share (framework/stages/STAGE/
// check.cpp; voxlab/function_checks.h, in the grader, says what a check is
// and records).
//
// Every check draws its inputs from its own std::mt19937 with a fixed seed.
// Raw 32-bit outputs are turned into numbers here (CheckRandom), never by
// <random>'s distributions, whose results the standard leaves to each
// library, and from no transcendental function (whose last bit varies
// between C libraries). Every random number is drawn in a statement of its
// own or in a braced list (whose order C++ fixes), and every input is then
// rounded (to float, or to a grid of powers of two), so that rounding
// differences between compilers (a fused multiply-add) almost never show.
// GLSL inputs are stored as the floats the GPU computed with.
//
// Random inputs stay away from the places where a function jumps (a flag
// that flips where a dot product is 0, a voxel boundary for nearest
// neighbour, a box widget's edge), except where a case puts an input
// exactly on such a place on purpose, in exact arithmetic: there the
// documented rule (">= 0 is inside", "ties go to the lower axis") decides,
// and an implementation that rounds differently elsewhere cannot lose.
//
// A stage registers its checks in its check.cpp:
//   VOXLAB_FUNCTION_CHECKS(mip) {
//       checks.add("mip_random_rays", "mip_ray() on random rays ...", runMipRays, compareProjection);
//   }
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "voxlab/function_check_info.h"
#include "voxlab/glsl_probe.h"
#include "voxlab/shader.h"

namespace voxlab::check {

using json = nlohmann::json;
using probe::GlslProbe;

// Cases a check runs (one pixel of a probe each).
constexpr int kCases = 200;

// ---------------------------------------------------------------------------
// Inputs

class CheckRandom {
public:
    explicit CheckRandom(std::uint32_t seed) : engine_(seed), seed_(seed) {}
    std::uint32_t seed() const { return seed_; }
    // [0, 1): mt19937's outputs are 32-bit integers, the same on every platform.
    double uniform() { return double(std::uint32_t(engine_())) / 4294967296.0; }
    double range(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    int index(int n) { return int(std::uint32_t(engine_()) % std::uint32_t(n)); }
    glm::dvec3 inBox(glm::dvec3 lo, glm::dvec3 hi) { return {range(lo.x, hi.x), range(lo.y, hi.y), range(lo.z, hi.z)}; }
    // Uniform on the sphere: a point of the cube, kept when inside the ball.
    glm::dvec3 unitVector() {
        for (;;) {
            const glm::dvec3 p = inBox(glm::dvec3(-1.0), glm::dvec3(1.0));
            const double length = glm::length(p);
            if (length > 0.1 && length <= 1.0) return p / length;
        }
    }

private:
    std::mt19937 engine_;
    std::uint32_t seed_;
};

// Numbers as the GPU gets them (rounded to float), and vectors as JSON.
double f32(double x);
glm::dvec3 f32(glm::dvec3 v);
glm::dvec3 unitF32(glm::dvec3 v);
glm::vec4 texel(glm::dvec3 v, double w = 0.0);
json vecJson(glm::dvec3 v);
glm::dvec3 vecOf(const json& j);

// Outputs: a NaN or an infinity becomes null here already, so a result
// reads the same before and after a trip through a file.
json number(double x);
json numbers(std::initializer_list<float> values);

// `seed` is recorded so that a failing case can be reproduced (the report shows it).
json checkJson(const std::string& name, const std::string& stage, std::uint32_t seed);
void addCase(json& check, const std::string& function, json input, json output);

// A C++ stage's call: NotImplemented propagates (the stage is a stub);
// any other exception is that case's output, and fails it.
json callStage(const std::function<json()>& call);

// Random volumes: values uniform in [0, 1), stored as data = value * scale
// + offset; as JSON for the report (layout and mapping spelled out).
probe::ProbeVolume randomVolume(CheckRandom& rng, glm::ivec3 dims, glm::dvec3 spacing, double scale, double offset);
json volumeJson(const probe::ProbeVolume& volume);

// ---------------------------------------------------------------------------
// Rays for the marching checks (a first hit, an isosurface hit, projections)
//
// The hit checks hand first_hit() or iso_hit() a Ray as clip_ray() leaves it
// (t_entry and t_exit where it enters and leaves the volume's box) and walk
// the README's samples t_entry + (m + 1/2) step. Their outputs jump where a
// sample's value equals the threshold or isovalue (the hit moves by a whole
// step) and where the number of samples changes, so each ray is drawn again
// until every value it reads keeps clear of those places: then a correct
// submission that rounds differently (t by accumulation, a midpoint as
// lo + (hi - lo)/2) gets the same hit, and only the hit's rounding differs.

// Programs for the marching probes: the GPU's filtering (as for the
// gradient check: the check sees this stage alone), skipping and sample
// counting off (the empty-space helpers return their argument).
const ShaderConstants kMarchConstants = {
    {"u_interpolation", 2}, {"u_skipping", 0}, {"u_count_samples", 0}, {"u_clip_plane", 0}};

// How close (data units) a value may come to the threshold or isovalue, and
// to the number of samples' jump (L / step + 1/2 an integer). A sample's
// position differs between correct implementations by ~1e-5 world units,
// its value by ~1e-5: 1e-3 leaves a factor of 100.
constexpr double kValueMargin = 1e-3;

constexpr double kCountMargin = 1e-3;

struct ProbeRay {
    glm::dvec3 origin{0.0}, direction{0.0};  // as the GPU gets them (floats)
    double tEntry = 0.0, tExit = 0.0;
};

// Runs a ray-marching probe (first hit, iso) on `rays` through `volume`:
// each case gets its ray's origin and t_entry, direction and t_exit.
probe::ProbeResults marchRays(const std::string& root, const std::string& fragment,
                              const probe::ProbeVolume& volume, const std::vector<ProbeRay>& rays,
                              const std::function<void(const ShaderProgram&, int)>& perCase);

// The probe volume's trilinear field in double, clamped to the border
// voxels: only to keep the inputs clear of jumps (see above).
double probeField(const probe::ProbeVolume& v, glm::dvec3 p);

// A random unit direction through `through` (inside the box [0, extent]),
// from `back` before it; t_entry and t_exit by the slab method in double,
// then rounded to float as the GPU gets them. t_entry is 0 where the origin
// lies inside the box, as clip_ray() leaves it.
ProbeRay boxRay(CheckRandom& rng, glm::dvec3 extent, glm::dvec3 through, double back);

// The i-th random ray of a marching check: every fourth starts inside the
// box (t_entry = 0), the others come from up to 2 units outside it.
ProbeRay marchingRay(CheckRandom& rng, glm::dvec3 extent, std::size_t i);
double sampleT(const ProbeRay& ray, double step, int m);

// floor(L / step + 1/2) samples (ray.glsl), or -1 where L / step + 1/2 is
// within kCountMargin of an integer (float rounding could add or drop one).
int clearSampleCount(const ProbeRay& ray, double step);
json rayInput(const ProbeRay& ray, double step);
json probeFlag(float v);

// kCases marching rays through a box of `extent`, each with a random step
// (0.2 to 0.9) that gives it at least one sample and no doubt about how
// many; `accepted`, when given, is called after each ray is kept (it may
// draw more numbers from `rng` for that ray).
void randomRays(CheckRandom& rng, glm::dvec3 extent, std::vector<ProbeRay>* rays, std::vector<double>* steps,
                const std::function<void()>& accepted = nullptr);

// A projection's check (`function`: one value per ray): kCases random rays
// through a random 6x7x5 volume of whole int16 values (the whole range
// -32768..32767, negative values included, as the handouts promise), with
// unequal spacings and random steps; each voxel's uniform number u in
// [0, 1) is first mapped by `skew` (u^3 makes most values low, so that a
// maximum that starts at 0 fails). Runs `stage`'s probe,
// stages/STAGE/STAGE_probe.frag.
json runProjection(const std::string& root, const std::string& stage, const std::string& function, std::uint32_t seed,
                   double (*skew)(double u) = nullptr);

// ---------------------------------------------------------------------------
// Comparison

double notANumber();

// One case's verdict: `delta` is the difference counted in "worst |Δ|"
// (NaN where it is not a number: a flag, a missing vertex).
struct CaseVerdict {
    bool pass = true;
    double delta = 0.0;
    std::string note;
};

CaseVerdict failure(const std::string& note);
bool isFiniteNumber(const json& j);

// Numbers, or arrays of them, agree where |a - e| <= absolute + relative |e|.
CaseVerdict compareNumbers(const json& expected, const json& actual, double absolute, double relative);
CaseVerdict compareExact(const json& expected, const json& actual);
bool readPoints(const json& list, std::vector<glm::dvec3>* points);

// The hit flags must agree; where neither hits, t and value are not part
// of the contract. *bothHit tells whether t must be compared.
CaseVerdict compareHitFlags(const json& e, const json& a, bool* bothHit);

// The same samples give the same values; a sample's position differs
// between correct implementations by float rounding (~1e-5 units), its
// value by at most the largest slope (65535 per ~0.8 units) times that,
// about 1: 8 data units (1.2e-4 of the range) allows it, while a sample
// more or fewer, or one at the wrong place, moves a value by thousands.
CaseVerdict compareProjection(const std::string&, const json&, const json& e, const json& a);

// ---------------------------------------------------------------------------
// Transfer functions for the compositing checks

// A random piecewise-linear transfer function over [0, 100]: control points
// at integer values (0 and 100 among them), so that its table of 101 entries,
// one per integer, is exact.
struct ProbeTransferFunction {
    std::vector<std::pair<int, glm::vec4>> points;  // value, (colour, opacity per unit length)
    std::vector<glm::vec4> table;                   // 101 entries
};

ProbeTransferFunction randomTransferFunction(CheckRandom& rng);
json transferFunctionJson(const ProbeTransferFunction& tf);

// ---------------------------------------------------------------------------
// A check: its run function records the cases (voxlab/function_checks.h),
// its compare function gives each case's verdict.
using RunFunction = json (*)(const std::string& implementationRoot);
using CompareFunction = CaseVerdict (*)(const std::string& function, const json& input, const json& expected,
                                        const json& actual);

struct CheckDefinition {
    FunctionCheckInfo info;
    RunFunction run;
    CompareFunction compare;
};

// What a stage's VOXLAB_FUNCTION_CHECKS adds its checks to; the stage is
// the folder's.
class StageChecks {
public:
    StageChecks(std::string stage, std::vector<CheckDefinition>* list) : stage_(std::move(stage)), list_(list) {}
    void add(const std::string& name, const std::string& description, RunFunction run, CompareFunction compare) {
        list_->push_back({{name, stage_, description}, run, compare});
    }

private:
    std::string stage_;
    std::vector<CheckDefinition>* list_;
};

}  // namespace voxlab::check

#define VOXLAB_FUNCTION_CHECKS(stage)                                     \
    namespace voxlab {                                                    \
    void stageChecks_##stage(check::StageChecks& checks);                 \
    }                                                                     \
    void voxlab::stageChecks_##stage(voxlab::check::StageChecks& checks)
