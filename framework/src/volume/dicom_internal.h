// voxlab (internal): the two halves of loadDicom.
//
// dicom_loader.cpp reads a series with GDCM in this process
// (loadDicomHere); dicom_child.cpp's loadDicom runs it in a forked child,
// because Debian's GDCM is built with its assert()s live: a damaged file can
// abort the process from inside GDCM (a truncated attribute header stops at
// gdcmExplicitDataElement.txx's `assert(0 && "Should not happen")`), and no
// exception can be caught instead. See dicom_child.cpp.
#pragma once

#include <cstdint>
#include <string>

#include "voxlab/volume.h"

namespace voxlab::detail {

// loadDicom's work, done here and now (errors: voxlab::Error).
Volume loadDicomHere(const std::string& path);

// Called before GDCM reads `file`: in loadDicom's child, it records the file
// so that a crash can be blamed on it; elsewhere it does nothing.
void dicomReading(const std::string& file);

// Called before each phase of reading with the memory that phase may
// allocate beyond what is allocated now: in loadDicom's child it caps the
// address space there (RLIMIT_AS), so that a damaged length field that makes
// GDCM allocate gigabytes ends in std::bad_alloc; elsewhere it does nothing.
void dicomMemoryBudget(std::uint64_t bytes);

}  // namespace voxlab::detail
