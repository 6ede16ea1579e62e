// voxlab: a student's upload, copied once into a folder the grader owns.
//
// What a student uploads is read exactly once, before anything is graded:
// copyUpload() copies it into a fresh folder, and from then on only that
// copy is read (finding the stage folders, each stage's own snapshot, the
// stub scan, the similarity report). Swapping or changing the upload while
// it is graded changes nothing.
//
// An upload is a folder, a .zip file, or a folder that holds one .zip file
// and nothing else but dot-files (Gradescope's shape for a zip). Only
// regular files and folders are copied, and no link is ever followed (each
// entry is opened with O_NOFOLLOW and checked on the open descriptor).
// Left out, and named in the submission's layout note: links, FIFOs,
// devices and sockets; files over the per-file cap; folders deeper than
// the depth cap. Left out silently: dot-files and dot-folders (.git,
// .DS_Store) and macOS's __MACOSX folders. Refused with a one-line reason
// (the submission is then graded as an error, 0 points): more bytes or
// entries than the caps.
//
// A zip is unpacked by unpackZip() through libarchive, writing every file
// itself: an entry that is a link, a hard link or a special file, or whose
// name is absolute or climbs out with "..", refuses the whole zip, and so
// do more entries than the cap, more bytes unpacked than the cap, or more
// than maxZipRatio bytes unpacked per byte of zip (a zip bomb). Names are
// made safe the same way for a folder and for a zip (valid UTF-8, no
// control characters), so a zip grades exactly as the folder it holds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "voxlab/grader.h"

namespace voxlab {

struct UploadLimits {
    std::uintmax_t maxTotalBytes = std::uintmax_t(256) << 20;  // copied or unpacked, in all
    std::size_t maxEntries = 20000;                            // files and folders (a zip's entries)
    int maxDepth = 16;                                         // folders below the upload's top
    std::uintmax_t maxFileBytes = std::uintmax_t(16) << 20;    // a larger file is left out
    double maxZipRatio = 100.0;                                // bytes unpacked per byte of zip...
    std::uintmax_t zipRatioFloor = std::uintmax_t(1) << 20;    // ...once more than this is unpacked
};

struct UploadCopy {
    std::string problem;               // why the upload cannot be graded; "" when it was copied
    std::vector<std::string> leftOut;  // "mip/x.glsl (a link)": what was not copied, and why
};

// Copies the upload at `upload` (a folder or a .zip file; the path itself
// may be a link, nothing inside it is followed) into the folder `into`,
// which this creates (mode 0700) and which must not exist (else it throws
// voxlab::Error: that is the grader's mistake, not the upload's).
UploadCopy copyUpload(const std::string& upload, const std::string& into, const UploadLimits& limits = {});

// Unpacks the zip file at `zip` into the folder `into` (created here; it
// must not exist). See above for what is refused.
UploadCopy unpackZip(const std::string& zip, const std::string& into, const UploadLimits& limits = {});

// An upload made ready for gradeSubmissions(): copied into `snapshot`
// (copyUpload), then brought into the shape of assignments/ from that copy
// (submissionRoot in assignment.h, for options.stages or every stage; loose
// files are placed in `snapshot`.placed). The Submission's folder is in the
// copy and its name is `name` made safe text. An upload that cannot be
// graded (refused by copyUpload, empty, or with no stage folder and no
// stage file anywhere) comes back with `problem` set, as does any exception
// on the way: this never throws for anything the upload holds.
Submission prepareSubmission(const std::string& name, const std::string& upload, const std::string& reportDir,
                             const std::string& snapshot, const GraderOptions& options,
                             const UploadLimits& limits = {});

}  // namespace voxlab
