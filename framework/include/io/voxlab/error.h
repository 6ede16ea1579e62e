// voxlab: one exception type for every user-facing failure.
//
// The message of a voxlab::Error is meant to be printed as-is, on one line,
// by the command line ("voxlab: <message>") and by the viewer's overlay. It
// should name the thing at fault (a file, a scene key, a shader line) and the
// problem, e.g. "bonsai.nrrd: truncated data: expected 16777216 bytes, got 512".
#pragma once

#include <stdexcept>
#include <string>

namespace voxlab {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Thrown by the stubs of student stages written in C++ (assignments/):
// "planeBoxPolygon is not yet implemented (a student stage)".
class NotImplemented : public Error {
public:
    explicit NotImplemented(const std::string& function)
        : Error(function + " is not yet implemented (a student stage)"), function_(function) {}
    const std::string& function() const { return function_; }

private:
    std::string function_;
};

}  // namespace voxlab
