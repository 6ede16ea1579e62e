// voxlab stage mip: its function check (voxlab/function_check_support.h).
#include "voxlab/function_check_support.h"

namespace voxlab::check {
namespace {

// Most values low (u^3): a maximum that starts at 0 fails many rays, whose
// results are negative.
double mostlyLow(double u) { return std::pow(u, 3.0); }
json runMipRays(const std::string& root) { return runProjection(root, "mip", "mip_ray", 0x5EED000Au, mostlyLow); }

}  // namespace
}  // namespace voxlab::check

VOXLAB_FUNCTION_CHECKS(mip) {
    using namespace voxlab::check;
    checks.add("mip_random_rays",
               "mip_ray() on random rays through a random 6x7x5 volume of int16 values (-32768..32767) with unequal "
               "spacings and random steps: rays from outside the box and from inside it; values within 8",
               runMipRays, compareProjection);
}
