// voxlab: reading demo decks (deck.h).
//
// A slide is its scene's JSON with the slide's own keys merged over it
// (RFC 7386 merge patch, nlohmann's merge_patch), then parsed by the scene
// reader: a slide is checked exactly as a scene file is, and there is one
// reader of scenes, not two.
#include "voxlab/deck.h"

#include <filesystem>

#include "json_text.h"
#include "voxlab/error.h"

namespace voxlab {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Slide readSlide(const json& j, const std::string& where, const std::string& deckDir) {
    if (!j.is_object()) throw Error(where + ": expected an object with \"scene\" and \"caption\"");
    if (!j.contains("scene")) throw Error(where + ": no \"scene\" (a scene file, or a scene written inline)");
    json scene;
    std::string baseDir = deckDir;
    const json& given = j["scene"];
    if (given.is_string()) {
        const std::string file = resolveDataPath(given.get<std::string>(), deckDir);
        scene = json_text::readJsonFile(file);
        baseDir = fs::path(file).parent_path().string();
    } else if (given.is_object()) {
        scene = given;
    } else {
        throw Error(where + ": \"scene\" must be a file name or an object");
    }
    if (!scene.is_object()) throw Error(where + ": the scene is not a JSON object");
    json patch = j;
    patch.erase("scene");
    patch.erase("caption");
    scene.merge_patch(patch);
    Slide slide;
    slide.scene = Scene::fromJson(scene, where, baseDir);
    if (j.contains("caption")) {
        if (!j["caption"].is_string()) throw Error(where + ": \"caption\" must be a string");
        slide.caption = j["caption"].get<std::string>();
    }
    return slide;
}

Deck parseDeck(const json& j, const std::string& path) {
    if (!j.is_object() || !j.contains("slides")) throw Error(path + ": a deck is an object with \"slides\": [...]");
    const json& slides = j["slides"];
    if (!slides.is_array() || slides.empty()) throw Error(path + ": \"slides\" must be a non-empty array");
    if (slides.size() > std::size_t(kMaxSlides))
        throw Error(path + ": " + std::to_string(slides.size()) + " slides (at most " + std::to_string(kMaxSlides) + ")");
    Deck deck;
    if (j.contains("title")) {
        if (!j["title"].is_string()) throw Error(path + ": \"title\" must be a string");
        deck.title = j["title"].get<std::string>();
    }
    const std::string dir = fs::path(path).parent_path().string();
    for (std::size_t i = 0; i < slides.size(); ++i)
        deck.slides.push_back(readSlide(slides[i], path + ": slide " + std::to_string(i + 1), dir));
    return deck;
}

}  // namespace

Deck loadDeck(const std::string& path) {
    const json j = json_text::readJsonFile(path);
    return json_text::escapedErrors([&] { return parseDeck(j, path); });
}

}  // namespace voxlab
