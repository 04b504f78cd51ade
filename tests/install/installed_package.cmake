# cmake -P script: build erkn in a scratch tree, install it into a prefix, DELETE the build tree,
# then use only the installed package: `erkn --version`, `erkn run` (the installed experiments
# program, writing charts and raw results), a C++ program built with pkg-config, a CMake
# consumer, and the Python package from the prefix.
# Inputs: SOURCE_DIR, WORK, CXX, LAUNCHER (may be empty), PYTHON (may be empty), PY_DIR,
# VERSION, CONSUMER_SOURCE.
include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)

set(build ${WORK}/build)
set(prefix ${WORK}/prefix)
file(REMOVE_RECURSE ${WORK})
set(options -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX} -DERKN_BUILD_TESTS=OFF
            -DERKN_BUILD_GENERATOR=OFF -DERKN_BUILD_BENCHMARKS=OFF -DERKN_WITH_MPI=OFF)
if(LAUNCHER)
  list(APPEND options -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
if(PYTHON)
  list(APPEND options -DPython_EXECUTABLE=${PYTHON})
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${build} ${options})
run(${CMAKE_COMMAND} --build ${build} -j 2)
run(${CMAKE_COMMAND} --install ${build} --prefix ${prefix})
file(REMOVE_RECURSE ${build})
if(EXISTS ${build})
  message(FATAL_ERROR "could not delete ${build}")
endif()

# The CLI and `erkn run`.
run(${prefix}/bin/erkn --version)
if(NOT out STREQUAL "erkn ${VERSION}\n")
  message(FATAL_ERROR "erkn --version printed '${out}', expected 'erkn ${VERSION}'")
endif()
run(${prefix}/bin/erkn run --problems P3 --methods SERKN2s4,verlet --steps 1/8,1/16
    --out ${WORK}/run)
foreach(f results.md charts/results.json charts/sweep.csv)
  if(NOT EXISTS ${WORK}/run/${f})
    message(FATAL_ERROR "the installed erkn run wrote no ${f}")
  endif()
endforeach()

# pkg-config: the header's example program, compiled and linked with the flags erkn.pc gives.
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
run(pkg-config --modversion erkn)
if(NOT out STREQUAL "${VERSION}\n")
  message(FATAL_ERROR "pkg-config --modversion erkn: '${out}'")
endif()
run(pkg-config --cflags --libs erkn)
separate_arguments(flags UNIX_COMMAND "${out}")
include(${CMAKE_CURRENT_LIST_DIR}/../runtime/consumer/header_example.cmake)
header_example(${prefix}/include/erkn/erkn.hpp example)
file(WRITE ${WORK}/pc/main.cpp "${example}")
run(${CXX} -std=c++20 -O2 ${WORK}/pc/main.cpp ${flags} -o ${WORK}/pc/app)
run(${WORK}/pc/app)

# CMake: find_package(erkn) from the prefix.
run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${WORK}/consumer -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_CXX_COMPILER=${CXX} -DEXAMPLE_SOURCE=${WORK}/pc/main.cpp -DERKN_TARGET=erkn::runtime)
run(${CMAKE_COMMAND} --build ${WORK}/consumer)
run(${WORK}/consumer/app)

# Python, from the prefix only.
if(PYTHON)
  set(ENV{PYTHONPATH} ${prefix}/${PY_DIR})
  run(${PYTHON} -c "import erkn, numpy as np; assert erkn.__file__.startswith('${prefix}'), erkn.__file__; \
s = erkn.solve(4.0, 'duffing', q0=[0.0], p0=[2.0], t_span=(0, 1.05), h=0.1); \
assert s.t[-1] == 1.05 and erkn.__version__ == '${VERSION}'; print(s)")
endif()
