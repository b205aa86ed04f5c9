# SPDX-License-Identifier: Apache-2.0
# cmake -DLIBRARY=librailtab_lookup.so -DNM=nm -P shared_symbols.cmake
# Lists the shared library's exported (dynamic, defined) symbols and fails unless every one is
# part of the API: a C function railtab_lookup_*, or railtab::lookup::* outside ::detail (with
# its vtables and type information). Also checks that the API itself is there.
execute_process(COMMAND ${NM} -D --defined-only --demangle ${LIBRARY}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc)
  message(FATAL_ERROR "nm failed: ${err}")
endif()
string(REPLACE "\n" ";" lines "${out}")
set(count 0)
set(bad "")
foreach(line IN LISTS lines)
  if(line STREQUAL "")
    continue()
  endif()
  # "<address> <type> <name>"; the version node line (type A) names the version script's node.
  string(REGEX REPLACE "^[0-9a-fA-F]+ ([A-Za-z]) (.*)$" "\\1;\\2" parts "${line}")
  list(GET parts 0 type)
  list(GET parts 1 name)
  if(type STREQUAL "A")
    continue()
  endif()
  math(EXPR count "${count} + 1")
  if(name MATCHES "^railtab_lookup_[a-z_]+$")
    continue()
  endif()
  string(REGEX REPLACE "^(typeinfo name for |typeinfo for |vtable for )" "" bare "${name}")
  # The qualified name is what precedes the parameter list (a private member of an API class
  # may take a detail:: type; the member itself is part of the class).
  string(REGEX REPLACE "\\(.*$" "" qualified "${bare}")
  if(qualified MATCHES "^railtab::lookup::" AND NOT qualified MATCHES "^railtab::lookup::detail::")
    continue()
  endif()
  string(APPEND bad "  ${line}\n")
endforeach()
message("shared_symbols: ${count} exported symbols in ${LIBRARY}")
if(bad)
  message(FATAL_ERROR "symbols outside the API are exported:\n${bad}")
endif()
foreach(required "railtab_lookup_open" "railtab_lookup_query_batch_checked"
        "railtab_lookup_status_text" "railtab::lookup::Table::load("
        "railtab::lookup::Table::query(" "typeinfo for railtab::lookup::LoadError")
  string(FIND "${out}" "${required}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "API symbol not exported: ${required}")
  endif()
endforeach()
message("shared_symbols: ok (only the C and C++ API are exported)")
