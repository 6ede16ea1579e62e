# Included by tests/CMakeLists.txt: builds the libFuzzer targets of
# tests/fuzz/ in build/fuzz (a clang sub-build, see tests/fuzz/CMakeLists.txt)
# and registers their short runs with CTest, label `fuzz`:
#   fuzz_NAME         NAME's seeds plus VOXLAB_FUZZ_CTEST_RUNS executions in all
#                     (fixed seed, so the same inputs every time); fails on a finding;
#   fuzz_NAME_long    VOXLAB_FUZZ_CTEST_LONG_RUNS executions from another fixed
#                     seed, labels `fuzz` and `heavy` (so CI runs it, and the
#                     default test run stays within its few minutes);
#   fuzz_NAME_canary  the harness's self-test: a planted exception must be
#                     reported as a finding.
# Nothing happens when clang++ cannot link a libFuzzer program (or Python 3 is
# missing): the g++ build and its tests are unchanged. -DVOXLAB_FUZZ=OFF turns
# it off by hand. Long runs: tools/fuzz.sh.
option(VOXLAB_FUZZ "Build and test the libFuzzer targets (tests/fuzz/) when clang++ is installed" ON)
set(VOXLAB_FUZZ_CTEST_RUNS 2000 CACHE STRING "Executions per fuzz target in its default CTest run")
set(VOXLAB_FUZZ_CTEST_LONG_RUNS 20000 CACHE STRING "Executions per fuzz target in its heavy CTest run")
if(NOT VOXLAB_FUZZ)
  return()
endif()

find_program(VOXLAB_FUZZ_CXX NAMES clang++-14 clang++ DOC "clang++ that builds the fuzz targets")
find_package(Python3 COMPONENTS Interpreter)
if(NOT VOXLAB_FUZZ_CXX OR NOT Python3_Interpreter_FOUND)
  message(STATUS "Fuzz targets: not built (need clang++ and python3)")
  return()
endif()

# Can this clang link a fuzzer with both sanitizers (libclang-rt-dev)?
# Asked once per compiler.
if(NOT VOXLAB_FUZZ_PROBED_CXX STREQUAL VOXLAB_FUZZ_CXX)
  set(probe ${CMAKE_CURRENT_BINARY_DIR}/fuzz_probe)
  file(WRITE ${probe}/probe.cpp
       "#include <cstddef>\n#include <cstdint>\n"
       "extern \"C\" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }\n")
  execute_process(
    COMMAND ${VOXLAB_FUZZ_CXX} -fsanitize=fuzzer,address,undefined probe.cpp -o probe
    WORKING_DIRECTORY ${probe} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  set(ok OFF)
  if(rc EQUAL 0)
    set(ok ON)
  endif()
  set(VOXLAB_FUZZ_USABLE ${ok} CACHE INTERNAL "clang++ links libFuzzer programs")
  set(VOXLAB_FUZZ_PROBED_CXX ${VOXLAB_FUZZ_CXX} CACHE INTERNAL "the clang++ probed")
endif()
if(NOT VOXLAB_FUZZ_USABLE)
  message(STATUS "Fuzz targets: not built (${VOXLAB_FUZZ_CXX} cannot link -fsanitize=fuzzer)")
  return()
endif()
message(STATUS "Fuzz targets: built with ${VOXLAB_FUZZ_CXX} in ${PROJECT_BINARY_DIR}/fuzz")

include(${CMAKE_CURRENT_LIST_DIR}/targets.cmake)
include(ExternalProject)
set(fuzz_bin ${PROJECT_BINARY_DIR}/fuzz)
ExternalProject_Add(voxlab_fuzzers
  SOURCE_DIR ${CMAKE_CURRENT_LIST_DIR}
  BINARY_DIR ${fuzz_bin}
  PREFIX ${PROJECT_BINARY_DIR}/fuzz-prefix
  CMAKE_ARGS -DCMAKE_CXX_COMPILER=${VOXLAB_FUZZ_CXX} -DCMAKE_BUILD_TYPE=RelWithDebInfo
             -DPython3_EXECUTABLE=${Python3_EXECUTABLE}
  BUILD_ALWAYS ON
  INSTALL_COMMAND "")

# fuzz_dicom forks a child per input, as loadDicom does in production (about
# 30 executions/s instead of thousands): fewer executions keep it short.
set(VOXLAB_FUZZ_CTEST_RUNS_dicom 100)
set(VOXLAB_FUZZ_CTEST_LONG_RUNS_dicom 1000)

set(runner ${CMAKE_CURRENT_LIST_DIR}/run_fuzzer.sh)
# Registers fuzz_NAME<suffix>: NAME's seeds plus the executions that the
# variable named `runs_var` says (or its _NAME variant where that is fewer),
# from libFuzzer seed `seed`, within `max_time` seconds.
function(voxlab_add_fuzz_run name suffix runs_var seed max_time labels timeout)
  set(runs ${${runs_var}})
  if(DEFINED ${runs_var}_${name} AND ${runs_var}_${name} LESS runs)
    set(runs ${${runs_var}_${name}})
  endif()
  add_test(NAME fuzz_${name}${suffix}
    COMMAND ${runner} ${fuzz_bin}/fuzz_${name} ${fuzz_bin}/corpus/${name} ${runs}
            -seed=${seed} -max_total_time=${max_time})
  set_tests_properties(fuzz_${name}${suffix} PROPERTIES LABELS "${labels}" TIMEOUT ${timeout})
endfunction()

foreach(name ${VOXLAB_FUZZ_TARGETS})
  voxlab_add_fuzz_run(${name} "" VOXLAB_FUZZ_CTEST_RUNS 1 120 fuzz 300)
  voxlab_add_fuzz_run(${name} _long VOXLAB_FUZZ_CTEST_LONG_RUNS 2 240 "fuzz;heavy" 400)

  add_test(NAME fuzz_${name}_canary
    COMMAND ${runner} ${fuzz_bin}/fuzz_${name} ${fuzz_bin}/corpus/${name} 100 -seed=1)
  set_tests_properties(fuzz_${name}_canary PROPERTIES LABELS fuzz TIMEOUT 60
    ENVIRONMENT "VOXLAB_FUZZ_CANARY=1;VOXLAB_FUZZ_ARTIFACTS=${fuzz_bin}/canary_artifacts"
    PASS_REGULAR_EXPRESSION "voxlab fuzz finding: exception other than voxlab::Error")
endforeach()
