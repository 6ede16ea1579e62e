#pragma once
// voxlab: the starter code's stubs, found in a stage's text. Below the
// renderer (the shader preprocessor numbers stub calls) and the grader.
#include <cstddef>
#include <string>
#include <vector>

namespace voxlab {

// The functions of a stage's files that still hold the starter code's stub
// (a `not_implemented();` call in GLSL, `throw NotImplemented(` in C++), by
// name, in file order.
std::vector<std::string> unimplementedFunctions(const std::string& stageFolder);

// If line `i` of a file calls the starter code's GLSL stub
// (`not_implemented();` alone on its line), the name of the function whose
// body it is in; else "". The shader preprocessor numbers each such call
// (PreprocessedShader::stubs), at most kMaxNumberedStubs per program (a
// set of them travels as the bits of a float).
std::string stubCallFunction(const std::vector<std::string>& lines, std::size_t i);
inline constexpr std::size_t kMaxNumberedStubs = 24;

// "gradient/: central_difference_gradient(); shading/: phong()", from
// "stage/function" names (grouped by stage, in their order).
std::string stubListText(const std::vector<std::string>& stubs);
// One line naming `stubs` (by stage folder), the functions the checkerboard
// stands for, and pointing to `voxlab check`; empty when there are none. The
// viewer shows it over the image while the checkerboard is on screen,
// `voxlab render` prints it.
std::string missingFunctionsNotice(const std::vector<std::string>& stubs);

}  // namespace voxlab
