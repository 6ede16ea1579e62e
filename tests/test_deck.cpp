// Demo decks (voxlab/deck.h): a slide is its scene with the slide's own keys
// laid over it, checked as a scene file is; errors name the deck and slide.
// The oracle is the scene file read on its own (Scene::load) and the keys
// written in the test.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "voxlab/deck.h"
#include "voxlab/error.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

class DeckFile : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(::testing::TempDir()) / ("voxlab_deck_" + std::to_string(getpid()));
        fs::create_directories(dir_);
    }
    std::string write(const std::string& name, const std::string& text) {
        std::ofstream((dir_ / name).string()) << text;
        return (dir_ / name).string();
    }
    std::string errorOf(const std::string& text) {
        try {
            loadDeck(write("bad.json", text));
        } catch (const Error& e) {
            return e.what();
        }
        return "(loaded)";
    }
    fs::path dir_;
};

TEST_F(DeckFile, ASlideIsItsSceneWithTheSlidesKeysOverIt) {
    write("base.json", R"({"dataset": "tooth.nrrd", "renderer": "mip", "camera": {"azimuth": 10, "elevation": 5},
                           "window": [10, 200]})");
    const Deck deck = loadDeck(write("talk.json", R"({"title": "T", "slides": [
        {"scene": "base.json", "caption": "as it is"},
        {"scene": "base.json", "renderer": "composite", "camera": {"azimuth": 40}, "transfer_function": "tf/tooth.json"},
        {"scene": {"dataset": "phantom:sphere:16", "renderer": "iso"}, "caption": "inline"}]})"));
    const Scene base = Scene::load((dir_ / "base.json").string());
    ASSERT_EQ(deck.slides.size(), 3u);
    EXPECT_EQ(deck.title, "T");
    EXPECT_EQ(deck.slides[0].caption, "as it is");
    EXPECT_EQ(deck.slides[0].scene.toJson(), base.toJson());
    const Scene& second = deck.slides[1].scene;
    EXPECT_EQ(second.renderer, "composite");
    EXPECT_EQ(second.camera.azimuth, 40.0);
    EXPECT_EQ(second.camera.elevation, 5.0) << "a key of the slide's camera replaced the whole camera";
    EXPECT_EQ(second.window, base.window);
    EXPECT_TRUE(second.transferFunction.has_value());
    EXPECT_FALSE(base.transferFunction.has_value());
    EXPECT_EQ(deck.slides[2].scene.renderer, "iso");
    EXPECT_EQ(deck.slides[2].scene.dataset, "phantom:sphere:16");
    EXPECT_EQ(deck.slides[2].caption, "inline");
}

TEST_F(DeckFile, TheShippedDeckLoads) {
    const Deck deck = loadDeck(std::string(VOXLAB_SOURCE_DIR) + "/datasets/decks/lecture.json");
    EXPECT_GE(deck.slides.size(), 5u);
    for (const Slide& slide : deck.slides) EXPECT_FALSE(slide.caption.empty());
}

TEST_F(DeckFile, MistakesAreOneLineNamingTheSlide) {
    EXPECT_EQ(errorOf("{}"), dir_.string() + "/bad.json: a deck is an object with \"slides\": [...]");
    EXPECT_NE(errorOf(R"({"slides": []})").find("must be a non-empty array"), std::string::npos);
    EXPECT_NE(errorOf(R"({"slides": [{"caption": "x"}]})").find("slide 1: no \"scene\""), std::string::npos);
    const std::string camera =
        errorOf(R"({"slides": [{"scene": {"dataset": "tooth.nrrd"}}, {"scene": {"dataset": "tooth.nrrd"},
                                 "camera": {"azimuth": "left"}}]})");
    EXPECT_NE(camera.find("slide 2"), std::string::npos) << camera;
    EXPECT_NE(camera.find("azimuth"), std::string::npos) << camera;
    EXPECT_NE(errorOf(R"({"slides": [{"scene": "nowhere.json"}]})").find("nowhere.json"), std::string::npos);
    EXPECT_NE(errorOf(R"({"slides": [{"scene": {"dataset": "tooth.nrrd"}, "caption": 3}]})").find("caption"),
              std::string::npos);
    std::string many = R"({"slides": [)";
    for (int i = 0; i <= kMaxSlides; ++i) many += std::string(i ? "," : "") + R"({"scene": {"dataset": "tooth.nrrd"}})";
    EXPECT_NE(errorOf(many + "]}").find("at most 500"), std::string::npos);
    EXPECT_NE(errorOf("{\"slides\": [").find("bad.json"), std::string::npos);
}

}  // namespace
}  // namespace voxlab::testing
