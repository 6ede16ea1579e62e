// voxlab stage average: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

json runAverageRays(const std::string& root) { return runProjection(root, "average", "average_ray", 0x5EED000Cu); }

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(average) {
    using namespace voxlab::check;
    checks.add("average_random_rays",
               "average_ray() on random rays through a random 6x7x5 volume of int16 values (-32768..32767) with "
               "unequal spacings and random steps: rays from outside the box and from inside it; values within 8",
               runAverageRays, compareProjection);
}
