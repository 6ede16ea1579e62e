// voxlab: a submission's C++ stage in a process of its own, for grading.
//
// When the grader grades a C++ stage, the submission's stage library is not
// loaded into the worker (which renders, and holds the results channel and
// the other stages' reference code). A stage host, `voxlab-stage-host LIB`,
// started by the worker, confines itself further (reads only its library
// and the system's, writes nothing), then loads the library and answers
// calls over a pipe. It is a program of its own, installed beside voxlab,
// that holds no stage code: the voxlab executable links the reference's C++
// stages in, and a library loaded into it could find them in memory. The worker points the graded stage's entries of
// cppStages() at stubs that call the host. The stage's code thus cannot
// write to the results channel, read what the worker holds, or change how
// the framework renders: it can only answer the calls it is asked.
//
// Protocol (native byte order; both ends are built from this tree), made
// for every function from VOXLAB_CPP_STAGE_FUNCTIONS (stage_host_protocol.h),
// so that a new C++ stage function needs nothing here:
//   request   one byte, the function's index in that list, then its
//             arguments: each as the bytes of its value (numbers, glm
//             vectors, a Camera), a pointer as the 8 values it points to
//             (cubeCase's corners);
//   response  'O' then the result (the bytes of its value; a vector as a
//             uint32 count <= 64 and its elements), or 'N'/'E' then uint32
//             length and the message of a NotImplemented / other exception.
//   batch     0xFF, the function's index, a uint32 count <= 16384 and each
//             call's arguments as above; 'O' then the count's results one
//             after another, or the first failing call's 'N'/'E'
//             (stage_library.h's StageBatch: marching cubes sends a slab of
//             cubes at a time).
// One call is one round trip (microseconds); a batch is one round trip for
// thousands of calls.
#pragma once

#include <string>
#include <vector>

#include "voxlab/error.h"

namespace voxlab {

// Thrown by the worker's stubs when the host crashed or stopped answering:
// the stage's C++ crashed, which the grader reports as such.
class StageCrashed : public Error {
public:
    using Error::Error;
};

// voxlab-stage-host beside this executable; throws voxlab::Error naming
// the path when it is missing.
std::string stageHostProgram();

// The worker's side: starts `host` (stageHostProgram()) for `library` and
// routes the named stage functions to it.
void useStageHost(const std::string& host, const std::string& library, const std::vector<std::string>& functions);

}  // namespace voxlab
