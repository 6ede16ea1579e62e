// voxlab: loadVolume — picks a loader by the "phantom:" prefix or the
// file's extension (case-insensitive).
#include "volume_io_util.h"

namespace voxlab {

Volume loadVolume(const std::string& pathOrSpec) {
    if (pathOrSpec.rfind("phantom:", 0) == 0) return makePhantom(pathOrSpec);
    if (pathOrSpec.empty()) throw Error("(empty path): no such file");

    detail::fileSize(pathOrSpec);  // "no such file", "is a directory", ...
    std::string ext = detail::fileExtension(pathOrSpec);
    if (ext == ".nrrd" || ext == ".nhdr") return loadNrrd(pathOrSpec);
    if (ext == ".fld") return loadFld(pathOrSpec);
    if (ext == ".dat") return loadDatRaw(pathOrSpec);
    std::string what = ext.empty() ? "no file extension" : "unknown volume format '" + ext + "'";
    detail::fail(pathOrSpec, what + " (supported: .nrrd, .nhdr, .fld, .dat, phantom:NAME)");
}

}  // namespace voxlab
