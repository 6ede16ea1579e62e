// Compiled into every stage library (see voxlab/stage_library.h), never into
// the framework. It hands the loader the addresses of the stage functions
// this library defines. The declarations are weak, so a function the
// submission's files do not define has the address null, and the loader
// keeps the framework's own.
#include "voxlab/marching_cubes.h"
#include "voxlab/proxy_geometry.h"
#include "voxlab/shear_warp.h"
#include "voxlab/splatting.h"
#include "voxlab/stage_library.h"

namespace voxlab {
__attribute__((weak)) std::vector<glm::dvec3> planeBoxPolygon(glm::dvec3, double, glm::dvec3, glm::dvec3);
__attribute__((weak)) int chooseSliceAxis(glm::dvec3);
__attribute__((weak)) int cubeCase(const double[8], double);
__attribute__((weak)) glm::dvec3 edgeCrossing(glm::dvec3, glm::dvec3, double, double, double);
__attribute__((weak)) SplatOrder splatOrder(glm::dvec3);
__attribute__((weak)) ShearWarp factorShearWarp(const Camera&, glm::ivec3, glm::dvec3);
}  // namespace voxlab

extern "C" voxlab::CppStages voxlab_stage_library_functions() {
    return {&voxlab::planeBoxPolygon, &voxlab::chooseSliceAxis, &voxlab::cubeCase, &voxlab::edgeCrossing,
            &voxlab::splatOrder, &voxlab::factorShearWarp};
}
