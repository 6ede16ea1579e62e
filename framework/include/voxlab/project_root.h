#pragma once
// voxlab: where the project's files are (shaders/, datasets/, reference/ or
// assignments/, framework/include for C++ stages).
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

namespace voxlab {

std::string projectRoot();

}  // namespace voxlab
