// voxlab: scene sections that stages bring. A stage whose technique needs
// its own part of a scene file (a key of the top-level object) declares it
// in framework/stages/<stage>/section.cpp, with the key, the lines of the
// scene format that document it, how it is read and how it is written:
//
//   VOXLAB_SCENE_SECTIONS(my_stage) {
//       sections.push_back({"my_key", "\"my_key\": {\"size\": 2}   // what it does",
//                           readMyKey, writeMyKey});
//   }
//
// section.cpp is built into the scene module (it may use only what a scene
// uses); the list of stages with one is generated from
// framework/stages/stages.cmake, in its order. Scene::fromJson reads each
// section present through its `read`, Scene::toJson writes it through its
// `write`, and `voxlab list` prints each section's documentation after the
// renderers.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "voxlab/error.h"
#include "voxlab/scene.h"

namespace voxlab {

// The scene reader's checked reads, for a section: every failure is a
// voxlab::Error that names the file and the key path
// ("scene.json: my_key.size: expected a number").
class SceneReader {
public:
    SceneReader(std::string where, std::string baseDir)
        : where_(std::move(where)), baseDir_(std::move(baseDir)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& message) const;
    // Fails on the first key of `object` (at `path`) that is not allowed.
    void onlyKeys(const nlohmann::json& object, const std::string& path,
                  std::initializer_list<const char*> allowed) const;
    double number(const nlohmann::json& j, const std::string& key) const;
    std::string string(const nlohmann::json& j, const std::string& key) const;
    glm::dvec3 vec3(const nlohmann::json& j, const std::string& key) const;
    // {"name": number or true/false}
    ParameterValues parameters(const nlohmann::json& j, const std::string& key) const;
    // A transfer function written out, or the path of its file.
    TransferFunction transferFunction(const nlohmann::json& j, const std::string& key) const;
    // A data file's name, resolved (resolveDataPath, from the scene's folder).
    std::string dataPath(const nlohmann::json& j, const std::string& key) const;

    // Runs f, adding the scene's location and `key` to any voxlab::Error.
    template <class F>
    auto located(const std::string& key, F f) const {
        try {
            return f();
        } catch (const Error& e) {
            fail(key, e.what());
        }
    }
    const std::string& where() const { return where_; }
    const std::string& baseDir() const { return baseDir_; }

private:
    std::string where_, baseDir_;
};

struct SceneSection {
    const char* key;  // the top-level key it owns
    const char* doc;  // its lines of the scene format, as in scene.h's comment
    // Reads the section's value into the scene (called when the key is present).
    void (*read)(const SceneReader& reader, const nlohmann::json& value, Scene& scene);
    // Writes the section into `scene` (the JSON object), when `from` has it.
    void (*write)(const Scene& from, nlohmann::json& scene);
};

// The sections of every stage that brings some, in the stages' order.
const std::vector<SceneSection>& stageSceneSections();

}  // namespace voxlab

// framework/stages/<stage>/section.cpp: VOXLAB_SCENE_SECTIONS(<stage>) { sections.push_back(...); }
#define VOXLAB_SCENE_SECTIONS(stage)                                            \
    namespace voxlab {                                                          \
    void stageSceneSections_##stage(std::vector<SceneSection>& sections);       \
    }                                                                           \
    void voxlab::stageSceneSections_##stage(std::vector<SceneSection>& sections)
