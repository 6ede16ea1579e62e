// Golden images: every scene of tests/golden/golden.json, rendered now, must
// match its stored image within the entry's tolerance. These are regression
// checks (the oracles that show the renderers are right are the other
// tests); they catch any change to what a real dataset looks like. On a
// mismatch the new render and a difference image are written to
// <build>/tests/golden_failures/ for inspection; regenerate on purpose with
// tools/update_golden.sh NAME.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "support/gl_fixture.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kGolden = fs::path(VOXLAB_SOURCE_DIR) / "tests" / "golden";

json manifest() {
    std::ifstream in(kGolden / "golden.json");
    return json::parse(in);
}

std::vector<std::string> goldenNames() {
    const json m = manifest();  // kept alive: the loop below refers into it
    std::vector<std::string> names;
    for (const json& e : m["images"]) names.push_back(e["name"].get<std::string>());
    return names;
}

struct Tolerance {
    int maxDifference = 0;   // grey levels of 255, per channel
    double maxFraction = 0;  // of the pixels
};

Tolerance toleranceOf(const std::string& name) {
    const json m = manifest();
    json t = m["default_tolerance"];
    for (const json& e : m["images"])
        if (e["name"] == name && e.contains("tolerance")) t.update(e["tolerance"]);
    return {t["max_difference"].get<int>(), t["max_fraction"].get<double>()};
}

// Volumes are shared between scenes: load each file once per run.
const Volume& cachedVolume(const std::string& path) {
    static std::map<std::string, Volume> cache;
    auto it = cache.find(path);
    if (it == cache.end()) it = cache.emplace(path, loadVolume(path)).first;
    return it->second;
}

class Golden : public GlTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(Golden, MatchesTheStoredImage) {
    const std::string name = GetParam();
    const Scene scene = Scene::load((kGolden / "scenes" / (name + ".json")).string());
    const Image want = loadPng((kGolden / "images" / (name + ".png")).string());
    engine().setVolume(cachedVolume(scene.dataset));
    const Image got = engine().render(scene);
    ASSERT_EQ(got.width, want.width);
    ASSERT_EQ(got.height, want.height);

    const Tolerance tol = toleranceOf(name);
    Image diff(got.width, got.height);
    int worst = 0, differing = 0;
    for (int y = 0; y < got.height; ++y)
        for (int x = 0; x < got.width; ++x) {
            int d = 0;
            for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(toByte(got.at(x, y)[c]) - toByte(want.at(x, y)[c])));
            worst = std::max(worst, d);
            if (d > tol.maxDifference) ++differing;
            // Differences amplified 8x, so that one grey level shows.
            diff.set(x, y, glm::vec4(glm::vec3(std::min(1.0f, d * 8.0f / 255.0f)), 1.0f));
        }
    const double fraction = double(differing) / (double(got.width) * got.height);
    if (fraction > tol.maxFraction) {
        const fs::path out = fs::current_path() / "golden_failures";
        fs::create_directories(out);
        savePng(got, (out / (name + ".png")).string());
        savePng(diff, (out / (name + "_diff.png")).string());
        ADD_FAILURE() << name << ": " << differing << " pixels (" << fraction * 100 << "%) differ by more than "
                      << tol.maxDifference << " grey levels (allowed " << tol.maxFraction * 100
                      << "%); worst difference " << worst << ". New render and difference image in " << out
                      << "; if the change is intended: tools/update_golden.sh " << name;
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, Golden, ::testing::ValuesIn(goldenNames()),
                         [](const auto& info) { return info.param; });

// The manifest, the scenes and the images list the same names: nothing is
// stored without being checked, and nothing is checked without being stored.
TEST(GoldenSet, ScenesImagesAndManifestAgree) {
    std::set<std::string> listed, scenes, images;
    for (const std::string& n : goldenNames()) EXPECT_TRUE(listed.insert(n).second) << n << " listed twice";
    for (const auto& f : fs::directory_iterator(kGolden / "scenes")) scenes.insert(f.path().stem().string());
    for (const auto& f : fs::directory_iterator(kGolden / "images")) images.insert(f.path().stem().string());
    EXPECT_EQ(scenes, listed);
    EXPECT_EQ(images, listed);
    // Every registered renderer has at least one golden image.
    for (const auto& r : rendererRegistry().all()) {
        bool found = false;
        for (const std::string& n : listed) found = found || n.rfind(r->id() + "_", 0) == 0;
        EXPECT_TRUE(found) << "no golden image for renderer " << r->id();
    }
}

}  // namespace
}  // namespace voxlab::testing
