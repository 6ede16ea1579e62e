// voxlab: the 1D transfer function (classification).
//
// A transfer function maps a data value v (in the data's own units, e.g.
// Hounsfield-like CT numbers, not 0..255) to a colour and an opacity. It is
// given by control points {value, color, alpha} and is piecewise linear
// between them, constant (clamped) outside them.
//
// Opacity is per unit length, where the unit is the volume's smallest voxel
// spacing; a sample taken with step `s` uses alpha' = 1 - (1 - alpha)^s
// (opacity correction; see the README's rendering conventions).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

namespace voxlab {

struct ControlPoint {
    double value = 0.0;
    glm::vec3 color{1.0f};
    float alpha = 1.0f;

    bool operator==(const ControlPoint& o) const {
        return value == o.value && color == o.color && alpha == o.alpha;
    }
};

// A baked lookup table: `size` RGBA entries; entry i holds the function at
// value lo + i*(hi-lo)/(size-1). Reading it with linear interpolation
// between entries reproduces the piecewise-linear function within
// `maxError` (checked on the CPU when baked).
//
// On the GPU the entries are stored row by row in a 2D texture
// kTransferFunctionRowLength texels wide (a 1D texture cannot hold the 65536
// entries a sharp ramp in 16-bit data needs), and the shader interpolates
// by hand, in float, at x = clamp((v - lo) / (hi - lo), 0, 1) * (size - 1):
// entries floor(x) and floor(x) + 1 mixed by fract(x). Value lo falls on
// entry 0 and hi on entry size-1; lookup() below computes exactly that on
// the CPU. (Hardware filtering would be cheaper, but GPUs blend with as few
// as 8 bits of weight, which alone can cost 1/512 at a steep ramp.)
// A degenerate range (hi <= lo when baked) is stored as [lo, lo + 1] with
// two equal entries, so the mapping above never divides by zero.
constexpr int kTransferFunctionRowLength = 4096;

// The 1D transfer function's short name, spelled here only: the --tf
// option, the viewer script's command and panel, and the presets' folder
// of a dataset folder (datasets/tf/).
inline constexpr const char* kTransferFunctionName = "tf";

struct TransferFunctionTable {
    double lo = 0.0;
    double hi = 1.0;
    int size = 0;
    std::vector<glm::vec4> rgba;
    double maxError = 0.0;

    // Linear interpolation between entries, as the GPU does it.
    glm::vec4 lookup(double value) const;
};

// At most this many control points. Far more than any hand-made function
// needs (and more than a 16-bit range has distinct values); it bounds the
// memory and the baking time a file can demand (a 229 MB file of points
// took 2.6 GB before). A 2D function has at most kMaxTf2dWidgets widgets.
constexpr std::size_t kMaxTransferFunctionPoints = 65536;

class TransferFunction {
public:
    TransferFunction() = default;
    // Throws voxlab::Error for a point that is not finite or outside 0..1,
    // or more than kMaxTransferFunctionPoints points.
    explicit TransferFunction(std::vector<ControlPoint> points);

    // Points sorted by value (stable for equal values, which make a step).
    const std::vector<ControlPoint>& points() const { return points_; }
    bool empty() const { return points_.empty(); }

    // Exact evaluation of the piecewise-linear function (rgb, alpha).
    glm::vec4 evaluate(double value) const;

    // Bakes a table over [lo, hi] whose linear interpolation stays within
    // `tolerance` of evaluate() everywhere in [lo, hi]: the size grows (by
    // powers of two, from 256 up to maxSize) until the worst error, found at
    // the control points where the function bends, is small enough. If even
    // maxSize is not enough, the maxSize table is returned and its maxError
    // says how far off it is (a step, two points at one value, cannot be
    // baked away: it costs at least half its jump, all of it on an entry).
    TransferFunctionTable bake(double lo, double hi, double tolerance = 0.5 / 255.0,
                               int maxSize = 1 << 20) const;

    // JSON: an array of {"value": v, "color": [r,g,b], "alpha": a}, or an
    // object {"points": [...], "name": "...", "description": "..."}. Every
    // point needs all three keys. Errors name the offending entry and key,
    // e.g. "tf.json: points[2].color: expected an array of 3 numbers in 0..1".
    static TransferFunction fromJson(const nlohmann::json& j, const std::string& where);
    // The same, for a function embedded under `key` in a larger document
    // (a scene): errors read "where: key[2].color: ...".
    static TransferFunction fromJson(const nlohmann::json& j, const std::string& where,
                                     const std::string& key);
    static TransferFunction load(const std::string& path);
    nlohmann::json toJson() const;

    // A grey ramp from (lo, alpha 0) to (hi, alpha 1).
    static TransferFunction ramp(double lo, double hi);

private:
    std::vector<ControlPoint> points_;
};

// The grey ramp compositing uses when a scene has no transfer function:
// opacity 0 at the window's low end to 0.1 per unit length at its high end
// (render_engine.h).
TransferFunction defaultCompositingFunction(glm::dvec2 window);

}  // namespace voxlab
