# Helpers that keep every module, test and tool built the same way.

# Warnings we hold every target to; see docs/architecture.md ("Build rules").
set(STEREOSCOUT_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual -Werror)
# FMA contraction changes floating-point results between x86 and aarch64; keeping it off
# makes a replay on the desk reproduce a run on the robot bit for bit.
set(STEREOSCOUT_DETERMINISM_FLAGS -ffp-contract=off)

# Precompiled headers. Every translation unit reaches Eigen and OpenCV's core through
# stereoscout/core, and every test GoogleTest: parsing them was most of a source file's compile
# time (docs/results.md, "CI and build times"). They are compiled once per build, in
# stereoscout_pch (and stereoscout_test_pch for test executables), and every target reuses
# them. Only headers from outside the tree: a change to ours does not rebuild them.
# A precompiled file the compiler finds incompatible is an error (CMake adds -Winvalid-pch,
# and warnings are errors). A source file with compile options of its own must skip them
# (SKIP_PRECOMPILE_HEADERS): compiled with its options, the dense matcher ran 7 times slower
# with them (modules/vision/CMakeLists.txt).
option(STEREOSCOUT_PRECOMPILED_HEADERS "Compile the heavy external headers once and reuse them" ON)
set(STEREOSCOUT_PCH_HEADERS <algorithm> <cmath> <cstdint> <cstdio> <memory> <string> <vector>
    <Eigen/Core> <Eigen/Geometry> <opencv2/core.hpp>)

function(stereoscout_target_defaults target)
  stereoscout_target_defaults_with(${target} stereoscout_pch)
endfunction()

# The same, with the precompiled headers of `pch` (stereoscout_pch or stereoscout_test_pch).
function(stereoscout_target_defaults_with target pch)
  target_compile_options(${target} PRIVATE ${STEREOSCOUT_WARNINGS} ${STEREOSCOUT_DETERMINISM_FLAGS})
  if(TARGET ${pch})
    target_precompile_headers(${target} REUSE_FROM ${pch})
  endif()
endfunction()

# stereoscout_add_precompiled_headers(): the targets that hold the shared precompiled headers;
# called once, after the packages are found and before any target uses them.
function(stereoscout_add_precompiled_headers)
  if(NOT STEREOSCOUT_PRECOMPILED_HEADERS)
    return()
  endif()
  stereoscout_add_pch_target(stereoscout_pch Eigen3::Eigen OpenCV::core)
  if(STEREOSCOUT_BUILD_TESTS)
    stereoscout_add_pch_target(stereoscout_test_pch Eigen3::Eigen OpenCV::core GTest::gtest HEADERS <gtest/gtest.h>)
  endif()
endfunction()

# stereoscout_add_pch_target(<name> <packages>... [HEADERS <more headers>...]): a target that
# compiles STEREOSCOUT_PCH_HEADERS (and HEADERS) with the packages' include directories.
function(stereoscout_add_pch_target name)
  cmake_parse_arguments(ARG "" "" "HEADERS" ${ARGN})
  add_library(${name} OBJECT ${PROJECT_SOURCE_DIR}/cmake/precompiled_headers.cpp)
  target_link_libraries(${name} PRIVATE ${ARG_UNPARSED_ARGUMENTS})
  target_compile_options(${name} PRIVATE ${STEREOSCOUT_WARNINGS} ${STEREOSCOUT_DETERMINISM_FLAGS})
  target_precompile_headers(${name} PRIVATE ${STEREOSCOUT_PCH_HEADERS} ${ARG_HEADERS})
endfunction()

# stereoscout_add_module(<name> SOURCES ... [DEPENDS ...])
# Creates library stereoscout_<name> (alias stereoscout::<name>) whose public headers live
# in modules/<name>/include/stereoscout/<name>/.
function(stereoscout_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  set(target stereoscout_${name})
  add_library(${target} STATIC ${ARG_SOURCES})
  add_library(stereoscout::${name} ALIAS ${target})
  target_include_directories(${target} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${target} PUBLIC ${ARG_DEPENDS})
  stereoscout_target_defaults(${target})
endfunction()

# stereoscout_add_test(<name> SOURCES ... [DEPENDS ...] [LABELS ...] [SLOW <gtest filter>])
# One GoogleTest executable per module; each TEST becomes its own CTest entry. Tests find
# the source tree and the data folder through tests/support (stereoscout/test/paths.hpp).
# SLOW names the tests (a --gtest_filter pattern, e.g. "Renderer.*:VisionFrontEnd.Same*")
# that take seconds; they get the label `slow` (instead of LABELS), which the emulated arm64
# run leaves out.
function(stereoscout_add_test name)
  cmake_parse_arguments(ARG "" "SLOW" "SOURCES;DEPENDS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} GTest::gtest GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support/include)
  target_compile_definitions(${name} PRIVATE
    STEREOSCOUT_TEST_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    STEREOSCOUT_TEST_DATA_DIR="${STEREOSCOUT_DATA_DIR}")
  stereoscout_target_defaults_with(${name} stereoscout_test_pch)
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  set(fast_filter "*")
  if(ARG_SLOW)
    set(fast_filter "-${ARG_SLOW}")
    gtest_discover_tests(${name}
      TEST_FILTER "${ARG_SLOW}"
      PROPERTIES LABELS slow
                 ENVIRONMENT "STEREOSCOUT_DATA_DIR=${STEREOSCOUT_DATA_DIR}"
      DISCOVERY_TIMEOUT 60)
  endif()
  gtest_discover_tests(${name}
    TEST_FILTER "${fast_filter}"
    PROPERTIES LABELS "${ARG_LABELS}"
               ENVIRONMENT "STEREOSCOUT_DATA_DIR=${STEREOSCOUT_DATA_DIR}"
    DISCOVERY_TIMEOUT 60)
endfunction()

# stereoscout_test_runs_command(<test target>): the test runs the stereoscout executable
# through stereoscout/test/command.hpp (under the cross emulator in a cross build).
function(stereoscout_test_runs_command target)
  list(JOIN CMAKE_CROSSCOMPILING_EMULATOR " " emulator)
  target_compile_definitions(${target} PRIVATE
    STEREOSCOUT_TEST_BINARY="$<TARGET_FILE:stereoscout>" STEREOSCOUT_TEST_BINARY_EMULATOR="${emulator}")
  add_dependencies(${target} stereoscout)
endfunction()

# stereoscout_add_benchmark(<name> SOURCES ... [DEPENDS ...])
function(stereoscout_add_benchmark name)
  if(NOT STEREOSCOUT_BUILD_BENCHMARKS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} benchmark::benchmark)
  stereoscout_target_defaults(${name})
endfunction()
