# cmake -P script: install the runtime component into PREFIX, extract the example program from
# the installed <erkn/erkn.hpp> (its lines that start with "//   "), then configure, build and
# run the consumer project against the installed package. Optional: COMPONENTS (more components
# to install), HEADER (the header holding the example), LINK_TARGET (what the program links) and
# LAUNCH (a command line that starts the program, e.g. "mpiexec -n 2").
if(NOT HEADER)
  set(HEADER erkn/erkn.hpp)
endif()
if(NOT LINK_TARGET)
  set(LINK_TARGET erkn::runtime)
endif()
separate_arguments(LAUNCH)
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGV}")
  endif()
endfunction()
# Configures the consumer in DIR asking for COMPONENTS with MPI made unfindable; sets ${out} to
# whether that succeeded.
function(configure_without_mpi dir components out)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${dir}
                  -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_CXX_COMPILER=${CXX}
                  -DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON -DERKN_COMPONENTS=${components}
                  -DEXAMPLE_SOURCE=${CONSUMER_BUILD}/example/main.cpp -DERKN_TARGET=erkn::runtime
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(rc EQUAL 0)
    set(${out} TRUE PARENT_SCOPE)
  else()
    set(${out} FALSE PARENT_SCOPE)
  endif()
endfunction()
file(REMOVE_RECURSE ${PREFIX} ${CONSUMER_BUILD})
foreach(component runtime ${COMPONENTS})
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --component ${component} --prefix ${PREFIX})
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/header_example.cmake)
header_example(${PREFIX}/include/${HEADER} example)
file(WRITE ${CONSUMER_BUILD}/example/main.cpp "${example}")

run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${CONSUMER_BUILD}/build
    -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release
    -DEXAMPLE_SOURCE=${CONSUMER_BUILD}/example/main.cpp -DERKN_TARGET=${LINK_TARGET}
    "-DERKN_COMPONENTS=${COMPONENTS}")
run(${CMAKE_COMMAND} --build ${CONSUMER_BUILD}/build)
run(${LAUNCH} ${CONSUMER_BUILD}/build/app)

# With the mpi component installed, find_package(erkn) without COMPONENTS mpi does not look for
# MPI (it configures with MPI unfindable), and with COMPONENTS mpi it does (then it cannot).
list(FIND COMPONENTS mpi mpi_index)  # (not IN_LIST: script mode has no CMP0057)
if(mpi_index GREATER -1)
  configure_without_mpi(${CONSUMER_BUILD}/runtime-only "" runtime_only)
  configure_without_mpi(${CONSUMER_BUILD}/mpi-asked mpi mpi_asked)
  if(NOT runtime_only OR mpi_asked)
    message(FATAL_ERROR "find_package(erkn) without MPI: runtime only configured: ${runtime_only}"
                        " (expected TRUE); COMPONENTS mpi configured: ${mpi_asked} (expected FALSE)")
  endif()
endif()
