// voxlab: loadVolume — picks a loader by the "phantom:" prefix or the
// file's extension (case-insensitive).
//
// DICOM has no one extension: a series is a folder of files named .dcm,
// .dicom, .ima, by number, or by UID ("1.3.12.2.1107.5.1.4.54023.30000..."
// looks like an extension). So a folder goes to loadDicom, and so do the
// DICOM extensions and any file that is not of another known format and holds
// the Part 10 magic "DICM" at bytes 128..131 (PS3.10 7.1: a 128-byte
// preamble, then the prefix). A folder named like another format
// ("x.nrrd/") keeps that format's "is a directory" error.
#include <filesystem>

#include "volume_io_util.h"

namespace voxlab {

namespace {

bool hasDicomMagic(const std::string& path) {
    const std::string head = detail::readPrefix(path, 132);
    return head.size() == 132 && head.compare(128, 4, "DICM") == 0;
}

bool isFolder(const std::string& path) {
    std::error_code ec;
    return std::filesystem::is_directory(path, ec);
}

}  // namespace

Volume loadVolume(const std::string& pathOrSpec) {
    if (pathOrSpec.rfind("phantom:", 0) == 0) return makePhantom(pathOrSpec);
    if (pathOrSpec.empty()) throw Error("(empty path): no such file");

    std::string ext = detail::fileExtension(pathOrSpec);
    const bool otherFormat = ext == ".nrrd" || ext == ".nhdr" || ext == ".fld" || ext == ".dat";
    if (!otherFormat && isFolder(pathOrSpec)) return loadDicom(pathOrSpec);

    detail::fileSize(pathOrSpec);  // "no such file", "is a directory", ...
    if (ext == ".nrrd" || ext == ".nhdr") return loadNrrd(pathOrSpec);
    if (ext == ".fld") return loadFld(pathOrSpec);
    if (ext == ".dat") return loadDatRaw(pathOrSpec);
    if (ext == ".dcm" || ext == ".dicom" || ext == ".ima" || hasDicomMagic(pathOrSpec))
        return loadDicom(pathOrSpec);
    std::string what = ext.empty() ? "no file extension" : "unknown volume format '" + ext + "'";
    detail::fail(pathOrSpec, what + " (supported: .nrrd, .nhdr, .fld, .dat, a DICOM series (a folder, "
                                    ".dcm), phantom:NAME)");
}

}  // namespace voxlab
