# SPDX-License-Identifier: Apache-2.0
# cmake -DGENERATOR_DIR=<generator/> -P CheckGeneratorIncludes.cmake
# Fails if a file in generator/ includes a header through "../": that would get around the
# per-library include paths that keep generator/'s folders to their allowed dependencies
# (generator/CMakeLists.txt, docs/architecture.md).
file(GLOB_RECURSE files ${GENERATOR_DIR}/*.cpp ${GENERATOR_DIR}/*.hpp)
set(bad "")
foreach(file ${files})
  file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]\\.\\./")
  if(lines)
    list(APPEND bad "${file}: ${lines}")
  endif()
endforeach()
if(bad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "generator/: include another folder's header as \"folder/file.hpp\" (allowed "
                      "folders only, docs/architecture.md), not through \"../\":\n  ${text}")
endif()
