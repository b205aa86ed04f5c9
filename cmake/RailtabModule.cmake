# SPDX-License-Identifier: Apache-2.0
# railtab_module(NAME DEPENDS dep...)
# One static library per layer of src/ (src/NAME/*.cpp), so each layer builds and tests on its own.
function(railtab_module name)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${name}/*.cpp)
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
# DIR becomes "_" in the names: tests/generator/sweep -> test_generator_sweep.
function(railtab_test dir)
  cmake_parse_arguments(ARG "" "" "LIBS;LABELS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/*_test.cpp)
  if(NOT sources)
    return()
  endif()
  string(REPLACE "/" "_" dir ${dir})
  add_executable(test_${dir} ${sources})
  target_include_directories(test_${dir} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_options(test_${dir} PRIVATE ${RAILTAB_WARNINGS})
  target_link_libraries(test_${dir} PRIVATE ${ARG_LIBS} GTest::gtest_main)
  target_compile_definitions(test_${dir} PRIVATE
    RAILTAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    RAILTAB_SHARED_DIR="${PROJECT_SOURCE_DIR}/../shared")
  gtest_discover_tests(test_${dir} PROPERTIES LABELS "${dir};${ARG_LABELS}"
                       DISCOVERY_TIMEOUT 60)
endfunction()
