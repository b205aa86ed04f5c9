# SPDX-License-Identifier: Apache-2.0
# cmake -DBUILD_DIR=... -DCONSUMER_SOURCE=... -DWORK_DIR=... -DTABLE=... -DGENERATOR=...
#       -DC_COMPILER=... -DCXX_COMPILER=... -DEXAMPLE=lookup_example.c -DSHARED=ON|OFF
#       -P run_consumer.cmake
# Installs railtab's lookup component to a fresh prefix, then uses it as an outside project
# would: (1) CMake find_package(railtab) + railtab::lookup (and railtab::lookup_shared), (2) the
# C example compiled with a plain `cc` line from pkg-config (shared library) and (3) with the
# documented static link line. Each program is run on TABLE.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --component lookup --prefix ${prefix})
run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_C_COMPILER=${C_COMPILER} -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer ${TABLE})
message("${last_output}")
if(SHARED)
  run(${WORK_DIR}/build/consumer_shared ${TABLE})
  message("shared: ${last_output}")
endif()

# Plain C, no CMake: the link lines of docs/lookup.md.
file(GLOB_RECURSE pc_files ${prefix}/*/railtab_lookup.pc)
list(GET pc_files 0 pc_file)
get_filename_component(pc_dir ${pc_file} DIRECTORY)
get_filename_component(lib_dir ${pc_dir} DIRECTORY)
set(pkg ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dir} pkg-config)
run(${pkg} --cflags railtab_lookup)
separate_arguments(cflags UNIX_COMMAND "${last_output}")
run(${pkg} --libs railtab_lookup)
separate_arguments(libs UNIX_COMMAND "${last_output}")
run(${pkg} --libs hdf5)
separate_arguments(hdf5_libs UNIX_COMMAND "${last_output}")
if(SHARED)
  # cc example.c $(pkg-config --cflags --libs railtab_lookup)
  run(${C_COMPILER} ${EXAMPLE} ${cflags} ${libs} -o ${WORK_DIR}/plain_c_shared)
  run(${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${lib_dir} ${WORK_DIR}/plain_c_shared ${TABLE})
  string(FIND "${last_output}" "batch: left fx" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "plain C (shared) printed:\n${last_output}")
  endif()
  message("plain C, shared library: ok")
endif()
# cc example.c $(pkg-config --cflags railtab_lookup) PREFIX/lib/librailtab_lookup.a \
#    $(pkg-config --libs hdf5) -lstdc++ -lm
run(${C_COMPILER} ${EXAMPLE} ${cflags} ${lib_dir}/librailtab_lookup.a ${hdf5_libs} -lstdc++ -lm
    -o ${WORK_DIR}/plain_c_static)
run(${WORK_DIR}/plain_c_static ${TABLE})
string(FIND "${last_output}" "batch: left fx" at)
if(at EQUAL -1)
  message(FATAL_ERROR "plain C (static) printed:\n${last_output}")
endif()
message("plain C, static library: ok")
message("consumer: all ok")
