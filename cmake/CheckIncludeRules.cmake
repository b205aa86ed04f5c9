# SPDX-License-Identifier: Apache-2.0
# cmake -DSOURCE_DIR=<repository root> -P CheckIncludeRules.cmake
# The dependency rules the link graph alone cannot enforce (docs/architecture.md, "How a forbidden
# include fails to compile"); every build runs it first (target railtab_check_includes):
# 1. No file in generator/ includes a header through "../": that would get around the per-library
#    include paths that keep generator/'s folders to their allowed dependencies.
# 2. Folders that must not see some headers although those are on their include path (src/ shares
#    one include root, so a link to railtab::core would let any src/ header in). Each rule names a
#    folder, the include prefixes its files may not use, and why.
# 3. File I/O in src/: only src/profile/formats/ includes the file headers (<fstream>, <cstdio>,
#    <filesystem>), and only to read; nothing in src/ writes a file or prints.
set(bad "")

file(GLOB_RECURSE generator_files ${SOURCE_DIR}/generator/*.cpp ${SOURCE_DIR}/generator/*.hpp)
foreach(file ${generator_files})
  file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]\\.\\./")
  if(lines)
    list(APPEND bad "${file}: ${lines} (include another folder's header as \"folder/file.hpp\")")
  endif()
endforeach()

# folder|forbidden include prefixes (alternatives)...|why
set(rules
  "generator/engine|profile|geometry|normal|tangential|wear|halfspace|vehicle|kernel|adaptive|eval|generate|the sweep engine is generic: the physics comes in through the kernel (SweepKernel) and its parameters"
  "generator/kernel|adaptive|eval|generate|the contact kernel sits below the adaptive grids, eval and generate"
  "src/profile/curves|profile/formats|profile/standard|the profile curves know no file format and no standard profile"
  "src/profile/standard|profile/formats|the standard profiles are built from their definitions, not read")
foreach(rule ${rules})
  string(REPLACE "|" ";" parts "${rule}")
  list(POP_FRONT parts folder)
  list(POP_BACK parts why)
  list(JOIN parts "|" forbidden)
  file(GLOB_RECURSE room_files ${SOURCE_DIR}/${folder}/*.cpp ${SOURCE_DIR}/${folder}/*.hpp)
  foreach(file ${room_files})
    file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"(${forbidden})/")
    if(lines)
      list(APPEND bad "${file}: ${lines} (${folder}/ may not include ${forbidden}: ${why})")
    endif()
  endforeach()
endforeach()

file(GLOB_RECURSE src_files ${SOURCE_DIR}/src/*.cpp ${SOURCE_DIR}/src/*.hpp ${SOURCE_DIR}/src/*.h)
foreach(file ${src_files})
  string(FIND "${file}" "${SOURCE_DIR}/src/profile/formats/" in_formats)
  if(NOT in_formats EQUAL 0)
    file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*<(fstream|cstdio|stdio\\.h|filesystem|iostream)>")
    if(lines)
      list(APPEND bad "${file}: ${lines} (file I/O and printing in src/ only in src/profile/formats/, which reads profile files)")
    endif()
  endif()
  file(STRINGS ${file} lines REGEX "(ofstream|fopen|std::filesystem::rename|std::cout|std::cerr)")
  if(lines)
    list(APPEND bad "${file}: ${lines} (src/ writes no file and prints nothing: the generator does, through generator/table/output_file.hpp)")
  endif()
endforeach()

if(bad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "an include or file access breaks the dependency rules (docs/architecture.md):\n  ${text}")
endif()
