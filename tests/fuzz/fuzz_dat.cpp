// libFuzzer target: volvis/QVis .dat descriptions of .raw files (loadDatRaw).
//
// The input holds both files, split at fuzz::kDataSeparator: the text
// description is written to volume.dat, the rest to volume.raw beside it.
// Seeds describe small crops of the bundled datasets in every Format
// spelling, with and without SliceThickness (tests/fuzz/make_corpus.py).
// See fuzz_common.h for what counts as a finding; tools/fuzz.sh runs it.
#include "fuzz_common.h"
#include "voxlab/volume.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string dat = fuzz::scratchFile("volume.dat");
    static const std::string raw = fuzz::scratchFile("volume.raw");
    const fuzz::TwoFiles files = fuzz::splitInput(data, size);
    fuzz::writeFile(dat, files.header);
    fuzz::writeFile(raw, files.data);
    fuzz::expectOnlyVoxlabErrors([&] {
        const Volume v = loadDatRaw(dat);
        fuzz::require(v.bytes().size() == v.voxelCount() * voxelTypeSize(v.type()),
                      "loaded volume: byte count disagrees with its dimensions");
    });
    return 0;
}
