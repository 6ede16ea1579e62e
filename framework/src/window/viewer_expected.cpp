// voxlab viewer: the split view of a student release, which has no
// reference/ to render. The right side there is the grading scene's
// expected image, shipped in expected/<stage>/<scene>.png by
// tools/make_student_release.sh: the left side renders the same scene file
// at the same size with the student's code, so "split" and "difference"
// show a real difference. Away from a grading scene the viewer says so
// instead of showing the student's own code as "reference".
#include <algorithm>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "voxlab/error.h"
#include "voxlab_gl.h"
#include "voxlab/image.h"
#include "voxlab/shader.h"
#include "viewer_state.h"

namespace voxlab::viewer {

namespace fs = std::filesystem;

bool comparesWithExpected(const State& s) { return s.split != SplitMode::Off && !s.hasReference; }

namespace {

// The name a stage's manifest gives the scene file `scene` (a grading
// scene's expected image is expected/<stage>/<name>.png), or its stem when
// the manifest does not list it.
std::string gradingSceneName(const fs::path& stageFolder, const fs::path& scene) {
    std::ifstream in(stageFolder / "grading.json");
    const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
    if (manifest.is_object() && manifest.contains("scenes") && manifest["scenes"].is_array())
        for (const nlohmann::json& entry : manifest["scenes"]) {
            if (!entry.is_object() || !entry.contains("scene") || !entry["scene"].is_string()) continue;
            const fs::path listed = (stageFolder / entry["scene"].get<std::string>()).lexically_normal();
            if (listed == scene && entry.contains("name") && entry["name"].is_string())
                return entry["name"].get<std::string>();
        }
    return scene.stem().string();
}

// The expected image of a scene file <stage>/scenes/<name>.json
// (assignments/ of the release, or a copy of a stage folder elsewhere),
// however the path was given: relative to the working folder or absolute.
std::string expectedImageFor(const std::string& scenePath) {
    if (scenePath.empty()) return "";
    std::error_code ec;
    fs::path scene = fs::weakly_canonical(fs::absolute(scenePath), ec);
    if (ec) scene = fs::absolute(scenePath).lexically_normal();
    if (scene.parent_path().filename() != "scenes") return "";
    const fs::path stageFolder = scene.parent_path().parent_path();
    const std::string stage = stageFolder.filename().string();
    const fs::path png = fs::path(projectRoot()) / "expected" / stage / (gradingSceneName(stageFolder, scene) + ".png");
    return fs::is_regular_file(png) ? png.string() : "";
}

void upload(State& s, const Image& image) {
    std::vector<unsigned char> bytes(std::size_t(image.width) * image.height * 4);
    for (int y = 0; y < image.height; ++y)  // GL's rows run bottom-up
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 4; ++c) {
                const float v = image.rgba[(std::size_t(y) * image.width + x) * 4 + c];
                bytes[(std::size_t(image.height - 1 - y) * image.width + x) * 4 + c] =
                    (unsigned char)(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
            }
    s.expected.texture.ensure();
    glBindTexture(GL_TEXTURE_2D, s.expected.texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace

void updateExpected(State& s) {
    // Once per scene file and dataset: a dataset loaded after the scene
    // file is not what the expected image shows.
    const std::string key = s.scenePath + "\n" + s.scene.dataset;
    if (key == s.expected.key) return;
    s.expected.key = key;
    const std::string png = expectedImageFor(s.scenePath);
    s.expected.path = png;
    s.expected.available = false;
    s.expected.why = "No reference in the student release.\nOpen a grading scene, "
                     "assignments/<stage>/scenes/*.json,\nto compare with its expected image.";
    if (png.empty()) return;
    try {
        const Image image = loadPng(png);
        s.expected.scene = Scene::load(s.scenePath);
        if (s.expected.scene.dataset != s.scene.dataset) return;
        s.expected.width = image.width, s.expected.height = image.height;
        s.expected.scene.width = image.width, s.expected.scene.height = image.height;
        upload(s, image);
        s.expected.available = true;
        s.expected.why.clear();
    } catch (const Error& e) {
        s.expected.why = e.what();
    }
}

}  // namespace voxlab::viewer
