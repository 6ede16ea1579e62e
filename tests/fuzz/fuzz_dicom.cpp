// libFuzzer target: a DICOM series of one or two files (loadDicom on a folder).
//
// The input holds the files, split at fuzz::kDataSeparator: the first is
// written to series/a.dcm, the rest (if any) to series/b.dcm, and the folder
// is loaded. With two slices the loader gets past "a volume needs at least 2
// slices" to the geometry checks and the pixel decoding. Seeds are pairs of
// neighbouring 4x4 slices of the bundled datasets in several transfer
// syntaxes (explicit and implicit VR little endian, big endian, RLE), with
// and without a rescale (tests/fuzz/make_corpus.py writes them byte by byte).
// A volume that loads must have 2 slices of the declared size.
//
// GDCM reads the files. By default loadDicom runs it in a child process, as
// in production (dicom_child.cpp): a crash inside GDCM must come back as a
// one-line voxlab::Error, and the fuzzer checks that contract, blind to
// GDCM's own coverage. With VOXLAB_DICOM_IN_PROCESS=1 GDCM runs in the
// fuzzer's process: coverage-guided into GDCM, and every assert() or crash in
// it is a finding (`VOXLAB_DICOM_IN_PROCESS=1 tools/fuzz.sh 100000 dicom`).
// See fuzz_common.h for what counts as a finding; tools/fuzz.sh runs it.
#include <filesystem>

#include "fuzz_common.h"
#include "voxlab/volume.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace voxlab;
    static const std::string folder = [] {
        const std::string f = fuzz::scratchFile("series");
        std::filesystem::create_directories(f);
        return f;
    }();
    const fuzz::TwoFiles files = fuzz::splitInput(data, size);
    fuzz::writeFile(folder + "/a.dcm", files.header);
    std::error_code ec;
    std::filesystem::remove(folder + "/b.dcm", ec);
    if (size != files.header.size()) fuzz::writeFile(folder + "/b.dcm", files.data);
    fuzz::expectOnlyVoxlabErrors([&] {
        const Volume v = loadDicom(folder);
        fuzz::require(v.dims().z == 2, "loaded series: not 2 slices");
        fuzz::require(v.bytes().size() == v.voxelCount() * voxelTypeSize(v.type()),
                      "loaded series: byte count disagrees with its dimensions");
        fuzz::require(v.minValue() <= v.maxValue(), "loaded series: min > max");
    });
    return 0;
}
