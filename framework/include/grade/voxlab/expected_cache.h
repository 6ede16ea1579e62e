// voxlab: the reference's expected outputs, kept between grading
// runs under the content hash of everything that makes them.
//
// Rendering the reference is half the time of grading one submission. The
// images and check results depend only on the worker program, the shaders,
// the datasets, the framework's headers and the reference's tree (manifests,
// GLSL and C++); so a key hashed from the bytes of all of those names them
// exactly, and a later run with the same key copies them instead of
// rendering them again. Under one key: each stage's outputs as grading
// renders them (hidden scenes included), as a self-check or a release
// renders them (without), and the compiled reference (reference_stages.so).
//
// The cache folder is $VOXLAB_EXPECTED_CACHE when set ("off" or empty turns
// the cache off), else $XDG_CACHE_HOME/voxlab/expected, else
// ~/.cache/voxlab/expected. Only the grader writes it: a submission's code
// runs in a sandbox that cannot write outside its work folder
// (child_process.h), and every entry is written in a temporary folder and
// renamed into place, so a run cut short never leaves half an entry. The
// eight most recently used keys are kept.
#pragma once

#include <optional>
#include <string>

namespace voxlab::expected_cache {

// The folder, or nothing when the cache is off.
std::optional<std::string> folder();

// The key for grading against `referenceRoot` run by `worker`: 32 hex
// digits (FNV-1a, 128 bits) over every byte named above.
std::string key(const std::string& worker, const std::string& referenceRoot);

// Copies the cached entry `name` (a stage's folder, or the library file)
// of `key` to `destination`; false when there is none.
bool restore(const std::string& key, const std::string& name, const std::string& destination);

// Keeps a copy of `source` (a folder or a file) as entry `name` of `key`.
// Never throws: a cache that cannot be written only costs time.
void store(const std::string& key, const std::string& name, const std::string& source);

}  // namespace voxlab::expected_cache
