# cmake -P script: `pip install` the checkout into a fresh virtual environment (with the system's
# site-packages, for NumPy and pytest; --no-index: nothing from the network), then run the
# README's Python example (python/tests/test_readme.py) against the installed package, from
# outside the source tree. Inputs: SOURCE_DIR, WORK, PYTHON, VERSION, LAUNCHER (may be empty).
set(RUN_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
run(${PYTHON} -m venv --system-site-packages ${WORK}/venv)
set(python ${WORK}/venv/bin/python)
if(LAUNCHER)
  set(ENV{ERKN_CMAKE_ARGS} "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
endif()
unset(ENV{PYTHONPATH})
run(${python} -m pip install --no-index --no-cache-dir ${SOURCE_DIR})
# (no ";" in the code: run() takes its arguments as a CMake list)
run(${python} -c "import erkn\nprint(erkn.__file__)\nprint(erkn.__version__)")
if(NOT out MATCHES "^${WORK}/venv/lib/[^\n]*/site-packages/erkn/__init__.py\n${VERSION}\n$")
  message(FATAL_ERROR "erkn imported from the wrong place or with the wrong version: ${out}")
endif()
set(ENV{ERKN_SOURCE_DIR} ${SOURCE_DIR})
set(ENV{MPLBACKEND} Agg)
run(${python} -m pytest -q -p no:cacheprovider ${SOURCE_DIR}/python/tests/test_readme.py)
message(STATUS "${out}")
