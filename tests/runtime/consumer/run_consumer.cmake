# cmake -P script: install the runtime component into PREFIX, extract the example program from
# the installed <erkn/erkn.hpp> (its lines that start with "//   "), then configure, build and
# run the consumer project against the installed package.
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGV}")
  endif()
endfunction()
file(REMOVE_RECURSE ${PREFIX} ${CONSUMER_BUILD})
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --component runtime --prefix ${PREFIX})

file(STRINGS ${PREFIX}/include/erkn/erkn.hpp lines)
set(example "")
foreach(line IN LISTS lines)
  if(line MATCHES "^//   (.*)$")
    string(APPEND example "${CMAKE_MATCH_1}\n")
  endif()
endforeach()
if(NOT example MATCHES "int main")
  message(FATAL_ERROR "no example program found in the installed erkn.hpp")
endif()
file(WRITE ${CONSUMER_BUILD}/example/main.cpp "${example}")

run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${CONSUMER_BUILD}/build
    -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release
    -DEXAMPLE_SOURCE=${CONSUMER_BUILD}/example/main.cpp)
run(${CMAKE_COMMAND} --build ${CONSUMER_BUILD}/build)
run(${CONSUMER_BUILD}/build/app)
