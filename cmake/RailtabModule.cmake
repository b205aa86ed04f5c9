# SPDX-License-Identifier: Apache-2.0
# railtab_module(NAME [DIR dir] DEPENDS dep...)
# One static library per layer of src/ (src/NAME/*.cpp, or src/DIR/*.cpp for a room of a layer such
# as profile/curves), so each layer builds and tests on its own.
function(railtab_module name)
  cmake_parse_arguments(ARG "" "DIR" "DEPENDS" ${ARGN})
  if(NOT ARG_DIR)
    set(ARG_DIR ${name})
  endif()
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${ARG_DIR}/*.cpp)
  if(sources)
    add_library(railtab_${name} STATIC ${sources})
    railtab_unity(railtab_${name})
    target_include_directories(railtab_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
    target_compile_options(railtab_${name} PRIVATE ${RAILTAB_WARNINGS})
    target_link_libraries(railtab_${name} PUBLIC ${ARG_DEPENDS})
  else()
    add_library(railtab_${name} INTERFACE)
    target_include_directories(railtab_${name} INTERFACE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(railtab_${name} INTERFACE ${ARG_DEPENDS})
  endif()
  add_library(railtab::${name} ALIAS railtab_${name})
endfunction()

# railtab_test(DIR LIBS lib... [LABELS label...] [ONE_PROCESS name suite...])
# tests/DIR/*_test.cpp -> one executable test_DIR, registered with CTest (label = DIR). A "/" in
# DIR becomes "_" in the names: tests/generator/engine -> test_generator_engine. ONE_PROCESS:
# railtab_gtest_tests below.
function(railtab_test dir)
  cmake_parse_arguments(ARG "" "" "LIBS;LABELS;ONE_PROCESS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/*_test.cpp)
  if(NOT sources)
    return()
  endif()
  string(REPLACE "/" "_" dir ${dir})
  add_executable(test_${dir} ${sources})
  railtab_test_program(test_${dir})
  target_include_directories(test_${dir} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_options(test_${dir} PRIVATE ${RAILTAB_WARNINGS})
  target_link_libraries(test_${dir} PRIVATE ${ARG_LIBS} GTest::gtest_main)
  target_compile_definitions(test_${dir} PRIVATE
    RAILTAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    RAILTAB_SHARED_DIR="${PROJECT_SOURCE_DIR}/../shared")
  railtab_gtest_tests(test_${dir} LABELS ${dir} ${ARG_LABELS} ONE_PROCESS ${ARG_ONE_PROCESS})
endfunction()

# railtab_test_program(TARGET): how a GoogleTest program is compiled: in unity batches
# (railtab_unity), with the test programs' precompiled headers (railtab_pch), and at -O1 in a
# Release build. A test program's own code is assertions, fixtures and loops that call the
# libraries, which keep the build type's optimisation (-O3); -O1 compiles it in less time and
# gives the same results (no -ffast-math: the same floating-point operations). The precompiled
# headers' donor (railtab_pch_donors) has the same -O1, as a precompiled header needs.
set(RAILTAB_TEST_PROGRAM_OPTIONS $<$<CONFIG:Release>:-O1>)
function(railtab_test_program target)
  railtab_unity(${target})
  railtab_pch(${target} program)
  target_compile_options(${target} PRIVATE ${RAILTAB_TEST_PROGRAM_OPTIONS})
endfunction()

# railtab_gtest_tests(TARGET LABELS label... [ONE_PROCESS name suite...])
# Registers the GoogleTest program TARGET with CTest: one CTest test per GoogleTest test (each its
# own process), except the ONE_PROCESS suites, which run together as the one CTest test NAME
# (TARGET --gtest_filter=suite.*:...). Those suites share a fixture that is costly to compute and
# computed once per process (a generated table): in one process it is computed once, not once per
# test. Their assertions are the same; the output names each GoogleTest test that fails, and
# `ctest -R NAME` (or TARGET --gtest_filter=...) runs them. COST: CTest starts the group first
# (it is one of the longest tests), so it does not finish alone at the end of a parallel run.
function(railtab_gtest_tests target)
  cmake_parse_arguments(ARG "" "" "LABELS;ONE_PROCESS" ${ARGN})
  set(exclude "")
  if(ARG_ONE_PROCESS)
    list(POP_FRONT ARG_ONE_PROCESS name)
    list(TRANSFORM ARG_ONE_PROCESS APPEND ".*")
    list(JOIN ARG_ONE_PROCESS ":" suites)
    add_test(NAME ${name} COMMAND ${target} --gtest_filter=${suites})
    set_tests_properties(${name} PROPERTIES LABELS "${ARG_LABELS}" COST 1000)
    set(exclude TEST_FILTER "-${suites}")
  endif()
  gtest_discover_tests(${target} ${exclude} PROPERTIES LABELS "${ARG_LABELS}" DISCOVERY_TIMEOUT 60)
endfunction()

# Precompiled headers (RAILTAB_PCH, ON by default). Nearly every file of the generator's libraries
# and of the tests includes nlohmann json (through engine/sweep.hpp) and the tests GoogleTest:
# parsed once per file, that is about 1.5 s of CPU each. Two small donor targets build the headers
# once, and the generator's libraries (railtab_pch(TARGET library)) and the test programs
# (railtab_pch(TARGET program)) reuse them (REUSE_FROM): a precompiled header is only valid with
# the flags it was built with, and the two kinds differ in one (-fPIC for the static libraries,
# -fPIE for the programs); every define the donors see (none of their own) the users see too, so
# gcc and clang accept it. src/ and the lookup stay without: they include none of these headers,
# and src/ keeps its rule of no file I/O headers (cmake/CheckIncludeRules.cmake). With ccache as
# the compiler launcher, these targets run it with the sloppiness its manual asks for precompiled
# headers (railtab_pch_ccache); without it ccache would compile them uncached.
set(RAILTAB_PCH_HEADERS <algorithm> <array> <cmath> <cstdint> <filesystem> <functional> <map> <memory>
    <optional> <string> <vector> <nlohmann/json.hpp>)
function(railtab_pch_donors)
  if(NOT RAILTAB_PCH)
    return()
  endif()
  add_library(railtab_pch_library STATIC ${PROJECT_SOURCE_DIR}/cmake/pch_donor.cpp)
  target_compile_options(railtab_pch_library PRIVATE ${RAILTAB_WARNINGS})
  target_link_libraries(railtab_pch_library PRIVATE nlohmann_json::nlohmann_json)
  target_precompile_headers(railtab_pch_library PRIVATE ${RAILTAB_PCH_HEADERS})
  railtab_pch_ccache(railtab_pch_library)
  if(RAILTAB_BUILD_TESTS)
    find_package(GTest REQUIRED)
    add_executable(railtab_pch_program ${PROJECT_SOURCE_DIR}/cmake/pch_donor.cpp)
    target_compile_options(railtab_pch_program PRIVATE ${RAILTAB_WARNINGS} ${RAILTAB_TEST_PROGRAM_OPTIONS})
    target_link_libraries(railtab_pch_program PRIVATE nlohmann_json::nlohmann_json GTest::gtest_main)
    target_precompile_headers(railtab_pch_program PRIVATE ${RAILTAB_PCH_HEADERS} <gtest/gtest.h>)
    railtab_pch_ccache(railtab_pch_program)
  endif()
endfunction()

# railtab_pch(TARGET library|program): TARGET reuses the donor's precompiled headers (above).
function(railtab_pch target kind)
  if(RAILTAB_PCH)
    target_precompile_headers(${target} REUSE_FROM railtab_pch_${kind})
    railtab_pch_ccache(${target})
  endif()
endfunction()

# railtab_pch_ccache(TARGET): when the C++ compiler launcher is ccache, run it with
# CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime (ccache's manual,
# "Precompiled headers"; the mtime and ctime: the header is built in the same build).
function(railtab_pch_ccache target)
  get_target_property(launcher ${target} CXX_COMPILER_LAUNCHER)
  if(launcher MATCHES "ccache")
    set_target_properties(${target} PROPERTIES CXX_COMPILER_LAUNCHER
      "${CMAKE_COMMAND};-E;env;CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime;${launcher}")
  endif()
endfunction()

# railtab_unity(TARGET): compiles the target's files in unity batches (RAILTAB_UNITY_BUILD, ON by
# default): every library (src/, lookup/, generator/), the test executables, the railtab program
# (generator/cli) and the Python module. Their files include the same headers (GoogleTest, Eigen,
# CLI11, nlohmann json, pybind11, fmt, HDF5, the standard library), which a batch parses and
# instantiates once instead of once per file; CI has no compiler cache, so its build is a clean
# one (docs/ci.md, "Building the test stage"). Two files of one batch must not define the same
# name: a file's helpers live in an anonymous namespace, a helper two files need lives once in a
# header, and test files whose helpers share a name each have their own named namespace
# (railtab::<file stem>). A file that is one long compile on its own stays out of the batches
# (SKIP_UNITY_BUILD_INCLUSION: the lookup's interpolation kernels), so the two cores share it.
function(railtab_unity target)
  if(RAILTAB_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()
