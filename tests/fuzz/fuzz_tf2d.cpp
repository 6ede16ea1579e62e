// libFuzzer target: 2D transfer functions (TransferFunction2D::load on a .json file).
//
// The input is the JSON text {"widgets": [{"type": "triangle"|"box", ...}]}.
// Seeds: datasets/tf2d/*.json plus one box widget.
// Besides the error contract (fuzz_common.h), a function that loads must
// survive toJson()/fromJson() unchanged, and evaluate() must give colours
// and opacities in 0..1 at the widgets' own values.
#include <nlohmann/json.hpp>

#include "fuzz_common.h"
#include "voxlab/transfer_function_2d.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string path = fuzz::scratchFile("tf2d.json");
    fuzz::writeFile(path, std::string(reinterpret_cast<const char*>(data), size));
    fuzz::expectOnlyVoxlabErrors([&] {
        const TransferFunction2D tf = TransferFunction2D::load(path);
        const nlohmann::json written = tf.toJson();
        TransferFunction2D again;
        try {
            again = TransferFunction2D::fromJson(written, "written");
        } catch (const Error& e) {
            fuzz::finding("a loaded 2D transfer function's toJson() does not load", e.what());
        }
        fuzz::require(again.widgets() == tf.widgets(), "2D transfer function round trip changes it",
                      written.dump());
        for (const Tf2dWidget& w : tf.widgets()) {
            for (double g : {0.0, w.gradientRange.x, w.gradientRange.y, 1.0}) {
                const glm::vec4 c = tf.evaluate(w.valueRange.x, g);
                for (int k = 0; k < 4; ++k)
                    fuzz::require(c[k] >= 0.0f && c[k] <= 1.0f, "evaluate() outside 0..1", written.dump());
            }
        }
    });
    return 0;
}
