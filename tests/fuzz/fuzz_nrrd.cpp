// libFuzzer target: NRRD with attached data (loadNrrd on a .nrrd file).
//
// The input is the whole file: the "NRRD000N" magic, header lines up to the
// first blank line, then the voxels (raw or gzip). Seeds: the bundled
// datasets' headers over small crops of their voxels, raw and gzip, little
// and big endian (tests/fuzz/make_corpus.py). A volume that loads must have
// the dimensions, type and byte count its header declares.
// See fuzz_common.h for what counts as a finding; tools/fuzz.sh runs it.
#include "fuzz_common.h"
#include "voxlab/volume.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string path = fuzz::scratchFile("input.nrrd");
    fuzz::writeFile(path, std::string(reinterpret_cast<const char*>(data), size));
    fuzz::expectOnlyVoxlabErrors([&] {
        const Volume v = loadNrrd(path);
        fuzz::require(v.bytes().size() == v.voxelCount() * voxelTypeSize(v.type()),
                      "loaded volume: byte count disagrees with its dimensions");
        fuzz::require(v.minValue() <= v.maxValue(), "loaded volume: min > max");
    });
    return 0;
}
