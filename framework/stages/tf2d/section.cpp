// voxlab stage tf2d: the 2D transfer function's section of a scene file
// (voxlab/scene_section.h), read into Scene::transferFunction2D: the widgets
// written out, or the path of a file of them (transfer_function_2d.h).
#include <nlohmann/json.hpp>

#include "voxlab/scene_section.h"

// The 2D transfer function's name everywhere (transfer_function_2d.h): this
// section's key, the --tf2d option, the viewer's command and panel, the
// presets' folder datasets/tf2d/.
const char* const voxlab::kTransferFunction2DName = "tf2d";

namespace {

using voxlab::TransferFunction2D;
using json = nlohmann::json;
const char* const kKey = voxlab::kTransferFunction2DName;

void read(const voxlab::SceneReader& in, const json& j, voxlab::Scene& scene) {
    if (!j.is_string()) {
        scene.transferFunction2D = TransferFunction2D::fromJson(j, in.where(), kKey);
        return;
    }
    const std::string path = in.dataPath(j, kKey);
    scene.transferFunction2D = in.located(kKey, [&] { return TransferFunction2D::load(path); });
}

void write(const voxlab::Scene& scene, json& out) {
    if (scene.transferFunction2D) out[kKey] = scene.transferFunction2D->toJson();
}

}  // namespace

VOXLAB_SCENE_SECTIONS(tf2d) {
    sections.push_back({kKey,
                        "\"tf2d\": {\"widgets\": [...]},            // 2D transfer function (value and gradient),\n"
                        "                                       // or a path; see transfer_function_2d.h",
                        read, write});
}
