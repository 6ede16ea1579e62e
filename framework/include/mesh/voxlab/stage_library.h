// voxlab: the C++ student stages, called through a table that a grader can
// re-point at a submission's code.
//
// A C++ stage's contract is a header in its stage folder,
// framework/stages/STAGE/include/voxlab/ (on the include path of the
// framework and of every stage library). C++ stages are compiled into the
// framework from the stage root (reference/ by default). The grader and `voxlab check` instead
// build a submission's stage .cpp files into a shared library together with
// framework/stage_library/stage_exports.cpp, and load it into the process
// that renders that submission: every function the library defines then
// replaces the linked-in one; functions it does not define stay as they were.
// The framework calls the stages only through cppStages().
#pragma once

#include <cstddef>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/stage_contracts.h"

namespace voxlab {

// The one list of the C++ stage functions, VOXLAB_CPP_STAGE_FUNCTIONS(X),
// is generated (framework/stages/stages.cmake) into voxlab/stage_contracts.h
// from the stage folders: each contract header defines its stage's part,
// VOXLAB_STAGE_FUNCTIONS_<stage>(X), with X(name, return type, parameter
// types). From it come the table's members, the linked-in table, the stubs
// that throw NotImplemented (stage_library.cpp), and the weak declarations
// and exports every stage library carries
// (framework/stage_library/stage_exports.cpp), and the calls across the
// stage host's pipe (stage_host_protocol.h). Adding a function: a line in its
// contract header.

// One pointer per C++ stage function.
struct CppStages {
#define VOXLAB_STAGE_MEMBER(name, Result, Parameters) Result(*name) Parameters = nullptr;
    VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_MEMBER)
#undef VOXLAB_STAGE_MEMBER
};

// The table in use: the linked-in stages unless a library was loaded.
const CppStages& cppStages();

// Many calls of one function at once, as marching cubes makes them (a slab
// of cubes, then the slab's new edges): the same results as calling the
// table's function on each call's arguments in order, stopping at the first
// call that throws. By default a loop over the table; where the function
// runs in a stage host (stage_host.h), one round trip for thousands of calls
// instead of one each. Every C++ stage function has its batch.
template <class F>
struct StageBatch;
template <class Result, class... Parameters>
struct StageBatch<Result(Parameters...)> {
    // One call's arguments (what a pointer points to must outlive the run).
    using Call = std::tuple<Parameters...>;
    void (*run)(const Call* calls, std::size_t count, Result* results) = nullptr;
};
struct CppStageBatches {
#define VOXLAB_STAGE_BATCH(name, Result, Parameters) StageBatch<Result Parameters> name;
    VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_BATCH)
#undef VOXLAB_STAGE_BATCH
};
const CppStageBatches& stageBatches();
// Replaces the batches that `batches` sets (those whose run is not null).
void overrideStageBatches(const CppStageBatches& batches);

// Whether `name` is a function of the table above ("planeBoxPolygon").
bool isStageFunction(const std::string& name);

// Points the named functions at stubs that throw NotImplemented. The grader
// does this for the stage being graded before loading the submission's
// library, so that a function the submission does not define is not
// implemented, rather than quietly the linked-in reference.
void clearStageFunctions(const std::vector<std::string>& names);

// Replaces the table's entries that `functions` sets (the non-null ones);
// returns their names.
std::vector<std::string> overrideStageFunctions(const CppStages& functions);

// Loads a stage library (dlopen) and takes the functions it defines.
// Returns their names. Throws voxlab::Error naming the library when it
// cannot be loaded (an undefined symbol, say).
std::vector<std::string> loadStageLibrary(const std::string& path);

// stage_exports.cpp compiled when the framework was built, or "" when that
// object is gone (the command below then compiles the source).
std::string stageExportsObject();

// framework/stage_library/stage_prelude.h as precompiled when the framework
// was built (the .gch beside it), or "" when that is gone.
std::string stagePreludeHeader();

// Where a stage library's headers are: each module's folder of
// framework/include (framework/include/MODULE, holding voxlab/*.h), then
// each stage's contract folder (framework/stages/STAGE/include), in name
// order; and, when the prebuilt exports are gone (their source is then
// compiled), the folder of the generated voxlab/stage_contracts.h where the
// mesh module's headers lack it (an installed tree has it there): the
// build's, while it is still there. The stage library's build reads these and nothing else of the
// framework's headers.
std::vector<std::string> stageIncludeDirs();

// The command that builds a stage library from `sources` (paths relative to
// `workingDir`, where it is run) into `output`: the compiler this framework
// was built with, its headers, position-independent and self-bound
// (-Bsymbolic), so that calls inside the library stay inside it. With a
// `prelude` (stagePreludeHeader()), that header is read first, precompiled.
std::vector<std::string> stageLibraryBuildCommand(const std::vector<std::string>& sources,
                                                  const std::string& output, const std::string& prelude = "");

}  // namespace voxlab
