// libFuzzer target: 1D transfer functions (TransferFunction::load on a .json file).
//
// The input is the JSON text: an array of {"value", "color", "alpha"} points
// or {"points": [...], "name", "description"}. Seeds: datasets/tf/*.json.
// Besides the error contract (fuzz_common.h), a function that loads must
// survive toJson()/fromJson() unchanged, and evaluate() and a small bake()
// over its own value range (the arithmetic the GPU table uses) must run
// clean under UBSan and give colours and opacities in 0..1.
#include <cmath>

#include <nlohmann/json.hpp>

#include "fuzz_common.h"
#include "voxlab/transfer_function.h"

namespace {

bool inUnit(const glm::vec4& c) {
    for (int k = 0; k < 4; ++k)
        if (!(c[k] >= 0.0f && c[k] <= 1.0f)) return false;
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string path = fuzz::scratchFile("tf.json");
    fuzz::writeFile(path, std::string(reinterpret_cast<const char*>(data), size));
    fuzz::expectOnlyVoxlabErrors([&] {
        const TransferFunction tf = TransferFunction::load(path);
        const nlohmann::json written = tf.toJson();
        TransferFunction again;
        try {
            again = TransferFunction::fromJson(written, "written");
        } catch (const Error& e) {
            fuzz::finding("a loaded transfer function's toJson() does not load", e.what());
        }
        fuzz::require(again.points() == tf.points(), "transfer function round trip changes it",
                      written.dump());

        const double lo = tf.points().front().value, hi = tf.points().back().value;
        for (double v : {lo, hi, (lo + hi) / 2, lo - 1, hi + 1})
            fuzz::require(inUnit(tf.evaluate(v)), "evaluate() outside 0..1", written.dump());
        const TransferFunctionTable table = tf.bake(lo, hi, 0.5 / 255.0, 1024);
        for (double v : {lo, hi, (lo + hi) / 2})
            fuzz::require(inUnit(table.lookup(v)), "baked lookup() outside 0..1", written.dump());
    });
    return 0;
}
