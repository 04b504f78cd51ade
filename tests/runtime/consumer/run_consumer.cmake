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
file(REMOVE_RECURSE ${PREFIX} ${CONSUMER_BUILD})
foreach(component runtime ${COMPONENTS})
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --component ${component} --prefix ${PREFIX})
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/header_example.cmake)
header_example(${PREFIX}/include/${HEADER} example)
file(WRITE ${CONSUMER_BUILD}/example/main.cpp "${example}")

run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${CONSUMER_BUILD}/build
    -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release
    -DEXAMPLE_SOURCE=${CONSUMER_BUILD}/example/main.cpp -DERKN_TARGET=${LINK_TARGET})
run(${CMAKE_COMMAND} --build ${CONSUMER_BUILD}/build)
run(${LAUNCH} ${CONSUMER_BUILD}/build/app)
