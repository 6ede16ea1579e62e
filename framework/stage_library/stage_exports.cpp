// Compiled into every stage library (see voxlab/stage_library.h), never into
// the framework. It hands the loader the addresses of the stage functions
// this library defines. The declarations are weak, so a function the
// submission's files do not define has the address null, and the loader
// keeps the framework's own.
#include "voxlab/stage_library.h"

namespace voxlab {
#define VOXLAB_STAGE_WEAK(name, Result, Parameters) __attribute__((weak)) Result name Parameters;
VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_WEAK)
#undef VOXLAB_STAGE_WEAK
}  // namespace voxlab

extern "C" voxlab::CppStages voxlab_stage_library_functions() {
    voxlab::CppStages offered;
#define VOXLAB_STAGE_OFFERED(name, Result, Parameters) offered.name = &voxlab::name;
    VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_OFFERED)
#undef VOXLAB_STAGE_OFFERED
    return offered;
}
