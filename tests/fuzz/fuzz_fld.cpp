// libFuzzer target: AVS field files (loadFld on a .fld file).
//
// The input is the whole file: the "# AVS field file" line, key=value lines,
// two form feeds, the voxels. Seeds: the headers of datasets/fld/*.fld over
// small crops of their voxels, byte and short (tests/fuzz/make_corpus.py).
// See fuzz_common.h for what counts as a finding; tools/fuzz.sh runs it.
#include "fuzz_common.h"
#include "voxlab/volume.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string path = fuzz::scratchFile("input.fld");
    fuzz::writeFile(path, std::string(reinterpret_cast<const char*>(data), size));
    fuzz::expectOnlyVoxlabErrors([&] {
        const Volume v = loadFld(path);
        fuzz::require(v.bytes().size() == v.voxelCount() * voxelTypeSize(v.type()),
                      "loaded volume: byte count disagrees with its dimensions");
    });
    return 0;
}
