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

# railtab_test(DIR LIBS lib... [LABELS label...])
# tests/DIR/*_test.cpp -> one executable test_DIR, registered with CTest (label = DIR). A "/" in
# DIR becomes "_" in the names: tests/generator/engine -> test_generator_engine.
function(railtab_test dir)
  cmake_parse_arguments(ARG "" "" "LIBS;LABELS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/*_test.cpp)
  if(NOT sources)
    return()
  endif()
  string(REPLACE "/" "_" dir ${dir})
  add_executable(test_${dir} ${sources})
  railtab_unity(test_${dir})
  target_include_directories(test_${dir} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_options(test_${dir} PRIVATE ${RAILTAB_WARNINGS})
  target_link_libraries(test_${dir} PRIVATE ${ARG_LIBS} GTest::gtest_main)
  target_compile_definitions(test_${dir} PRIVATE
    RAILTAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    RAILTAB_SHARED_DIR="${PROJECT_SOURCE_DIR}/../shared")
  gtest_discover_tests(test_${dir} PROPERTIES LABELS "${dir};${ARG_LABELS}"
                       DISCOVERY_TIMEOUT 60)
endfunction()

# railtab_unity(TARGET): compiles the target's files in unity batches (RAILTAB_UNITY_BUILD, ON by
# default): used for the test executables, the railtab program (generator/cli) and the Python
# module, whose files each include the same heavy headers (GoogleTest, Eigen, CLI11, nlohmann
# json, pybind11), so a batch parses and instantiates them once instead of once per file (the
# test executables, the program and the module take about a third of the CPU time to build;
# docs/reliability.md). The libraries (src/, lookup/, generator/ libraries) are built file by file
# as before, with the same flags. Two files of one batch must not define the same name: a test
# file's helpers live in an anonymous namespace, and files whose helpers share a name each have
# their own named namespace (railtab::<file stem>).
function(railtab_unity target)
  if(RAILTAB_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()
