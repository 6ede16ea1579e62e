// The headers every C++ stage file reads anyway (through voxlab/error.h and
// its stage's header), precompiled once when the framework is built, so that
// building a student's stage library parses none of them again: about
// 0.45 s of the 0.45 to 0.65 s a stage file takes (docs/grading.md).
//
// stageLibraryBuildCommand forces it in front of the stage's files
// (-include, the .gch beside it) when the .gch is there. Only the C++
// standard library and GLM: nothing of voxlab's, so that no name a stage
// file could define is taken. A file that does not build with it is built
// again as written (stage_job.cpp), and that build's messages are the ones
// reported. (No include guard: it is only ever forced in, once.)

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
