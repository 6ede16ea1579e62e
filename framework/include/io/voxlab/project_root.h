#pragma once
// voxlab: where the project's files are (shaders/, datasets/, reference/ or
// assignments/, framework/include/MODULE for C++ stages).
//
// The root is, in order:
//   1. $VOXLAB_ROOT when it is set;
//   2. found from the running executable: the first of its folder's
//      ancestors (up to four levels) that holds share/voxlab/shaders (an
//      installed tree: <prefix>/bin/voxlab reads <prefix>/share/voxlab) or
//      shaders/ itself (a checkout, with its build folder inside it, moved
//      or copied anywhere);
//   3. the source tree this was built from, as a last resort (a build
//      folder outside the checkout).
// Nothing here depends on the scene or the renderer: every module may ask.
#include <string>
#include <vector>

namespace voxlab {

std::string projectRoot();

// Where a stage's framework side lives: <root>/framework/stages/<stage>/
// holds its renderer, its function check and its own shaders (entry, probe,
// precomputation passes). Shaders there are named "stages/<stage>/FILE".
std::string stagesRoot();
// The folders of the framework's own shaders: shaders/ (the shared GLSL and
// the engine's passes) and stagesRoot(). What a worker may read, what the
// expected outputs depend on, what is checked for both GLSL dialects.
std::vector<std::string> frameworkShaderFolders();
// Whether `path` names a shader file: .glsl, .frag or .vert (what a stage
// folder offers the shader library, the grading worker and the install).
bool isShaderFile(const std::string& path);

}  // namespace voxlab
