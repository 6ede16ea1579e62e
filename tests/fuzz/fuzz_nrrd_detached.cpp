// libFuzzer target: NRRD with detached data (loadNrrd on a .nhdr header
// whose "data file:" names a second file).
//
// The input holds both files, split at fuzz::kDataSeparator: the header is
// written to header.nhdr and the rest to data.raw beside it. Seeds name
// "data file: data.raw" with raw and gzip encodings, byte skips and both
// endians (tests/fuzz/make_corpus.py); the fuzzer is free to name other
// files, including the header itself or a missing one.
// See fuzz_common.h for what counts as a finding; tools/fuzz.sh runs it.
#include "fuzz_common.h"
#include "voxlab/volume.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string header = fuzz::scratchFile("header.nhdr");
    static const std::string raw = fuzz::scratchFile("data.raw");
    const fuzz::TwoFiles files = fuzz::splitInput(data, size);
    fuzz::writeFile(header, files.header);
    fuzz::writeFile(raw, files.data);
    fuzz::expectOnlyVoxlabErrors([&] {
        const Volume v = loadNrrd(header);
        fuzz::require(v.bytes().size() == v.voxelCount() * voxelTypeSize(v.type()),
                      "loaded volume: byte count disagrees with its dimensions");
    });
    return 0;
}
