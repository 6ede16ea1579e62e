// libFuzzer target: demo decks (loadDeck on a deck file).
//
// The input is the deck's JSON text. Its slides' scene files and data names
// resolve against the scratch folder, then the project's datasets/ (so the
// seeds' "scenes/default.json" and "tf/bonsai.json" are found; volumes are
// not loaded). Seeds: datasets/decks/*.json and a deck with every kind of
// slide (make_corpus.py). Besides the error contract (fuzz_common.h), a deck
// that loads has at least one slide and no more than kMaxSlides.
#include "fuzz_common.h"
#include "voxlab/deck.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string path = fuzz::scratchFile("deck.json");
    fuzz::writeFile(path, std::string(reinterpret_cast<const char*>(data), size));
    fuzz::expectOnlyVoxlabErrors([&] {
        const Deck deck = loadDeck(path);
        fuzz::require(!deck.slides.empty() && deck.slides.size() <= std::size_t(kMaxSlides),
                      "a loaded deck's slide count is out of bounds", std::to_string(deck.slides.size()));
    });
    return 0;
}
