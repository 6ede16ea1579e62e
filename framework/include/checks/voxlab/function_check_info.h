// voxlab: a function check's name, its stage and what it checks
// (voxlab/function_checks.h lists them; a stage's check.cpp adds its own
// through voxlab/function_check_support.h).
#pragma once
#include <string>

namespace voxlab {

struct FunctionCheckInfo {
    std::string name, stage, description;
};

}  // namespace voxlab
