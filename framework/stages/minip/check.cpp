// voxlab stage minip: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// Most values high (1 - u^3): a minimum that starts at 0 fails many rays,
// whose results are positive.
double mostlyHigh(double u) { return 1.0 - std::pow(u, 3.0); }
json runMinipRays(const std::string& root) { return runProjection(root, "minip", "minip_ray", 0x5EED000Bu, mostlyHigh); }

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(minip) {
    using namespace voxlab::check;
    checks.add("minip_random_rays",
               "minip_ray() on random rays through a random 6x7x5 volume of int16 values (-32768..32767) with unequal "
               "spacings and random steps: rays from outside the box and from inside it; values within 8",
               runMinipRays, compareProjection);
}
