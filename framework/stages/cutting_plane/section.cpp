// voxlab stage cutting_plane: its section of a scene file (voxlab/scene_section.h),
// read into Scene::cuttingPlane; the engine draws the two half-spaces.
#include <nlohmann/json.hpp>

#include "voxlab/scene_section.h"

namespace {

using voxlab::CuttingPlane;
using voxlab::SceneReader;
using json = nlohmann::json;

constexpr const char* kKey = "cutting_plane";  // spelled here only

void readOtherSide(const SceneReader& in, const json& o, CuttingPlane& c) {
    const std::string key = std::string(kKey) + ".other_side";
    if (!o.is_object()) in.fail(key, "expected an object {\"renderer\", \"transfer_function\", \"parameters\"}");
    in.onlyKeys(o, key, {"renderer", "transfer_function", "parameters"});
    if (o.contains("renderer")) c.otherRenderer = in.string(o["renderer"], key + ".renderer");
    if (o.contains("transfer_function"))
        c.otherTransferFunction = in.transferFunction(o["transfer_function"], key + ".transfer_function");
    if (o.contains("parameters")) c.otherParameters = in.parameters(o["parameters"], key + ".parameters");
}

void read(const SceneReader& in, const json& j, voxlab::Scene& scene) {
    if (!j.is_object()) in.fail(kKey, "expected an object {\"point\", \"normal\", \"other_side\"}");
    in.onlyKeys(j, kKey, {"point", "normal", "other_side"});
    CuttingPlane c;
    if (j.contains("point")) c.point = in.vec3(j["point"], std::string(kKey) + ".point");
    if (j.contains("normal")) c.normal = in.vec3(j["normal"], std::string(kKey) + ".normal");
    if (glm::length(c.normal) <= 0.0) in.fail(std::string(kKey) + ".normal", "must not be zero");
    if (j.contains("other_side")) readOtherSide(in, j["other_side"], c);
    scene.cuttingPlane = c;
}

void write(const voxlab::Scene& scene, json& out) {
    if (!scene.cuttingPlane) return;
    const CuttingPlane& c = *scene.cuttingPlane;
    json cut = {{"normal", {c.normal.x, c.normal.y, c.normal.z}}};
    if (c.point) cut["point"] = {c.point->x, c.point->y, c.point->z};
    json other = {{"renderer", c.otherRenderer}, {"parameters", json::object()}};
    for (const auto& [name, value] : c.otherParameters) other["parameters"][name] = value;
    if (c.otherTransferFunction) other["transfer_function"] = c.otherTransferFunction->toJson();
    cut["other_side"] = other;
    out[kKey] = cut;
}

}  // namespace

VOXLAB_SCENE_SECTIONS(cutting_plane) {
    sections.push_back({kKey,
                        "\"cutting_plane\": {                     // splits the view in two half-spaces\n"
                        "  \"point\": [128, 128, 64],             // voxel coordinates (default: the centre)\n"
                        "  \"normal\": [1, 0, 0],                 // world direction; this scene's renderer\n"
                        "                                       // draws the side it points into\n"
                        "  \"other_side\": {\"renderer\": \"mip\",    // or \"none\": the other side is invisible\n"
                        "                 \"transfer_function\": \"tf/bonsai.json\", \"parameters\": {}}\n"
                        "}",
                        read, write});
}
