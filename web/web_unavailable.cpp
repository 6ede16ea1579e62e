// voxlab in the browser: what the browser build does not offer, as the
// one-line errors the native code's callers already show.
#include <string>

#include "voxlab/error.h"
#include "voxlab/volume.h"

namespace voxlab {

// DICOM (native: dicom_loader.cpp, through GDCM, which is not built for
// wasm32). A series is a folder, which a page cannot be handed anyway.
Volume loadDicom(const std::string& path) {
    throw Error(path + ": DICOM series are read by the native voxlab only; convert the series "
                "to NRRD first, or use a bundled dataset");
}

}  // namespace voxlab
