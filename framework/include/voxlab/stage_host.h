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
// Protocol (native byte order; both ends are built from this tree):
//   request   one byte, the function ('P' planeBoxPolygon, 'A' chooseSliceAxis,
//             'C' cubeCase, 'X' edgeCrossing, 'S' splatOrder, 'W'
//             factorShearWarp), then its arguments as doubles (10 for 'P', 3
//             for 'A' and 'S', 9 for 'C': the 8 values and the isovalue, 9 for
//             'X': a, b, va, vb, isovalue, 22 for 'W': the camera's position,
//             forward, right, down, pixel scale, width, height, projection
//             (0 orthographic), then dims and spacing);
//   response  'O' then the result ('P': uint32 count <= 64, then 3 doubles a
//             point; 'A' and 'C': int32; 'X': 3 doubles; 'S': 6 int32, the
//             axes then the steps; 'W': 17 doubles, axis, front, shear,
//             offset, size and the warp's 9, column by column), or 'N'/'E' then
//             uint32 length and the message of a NotImplemented / other
//             exception.
//   batches  'c' (cubeCase) and 'x' (edgeCrossing): uint32 count <= 16384,
//             then 8 doubles a call (the 8 values; a, b, va, vb) and one
//             isovalue; 'O' then count int32 / count points of 3 doubles, or
//             the first failing call's 'N'/'E' (stage_library.h's
//             StageBatches: marching cubes sends a slab of cubes at a time).
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
