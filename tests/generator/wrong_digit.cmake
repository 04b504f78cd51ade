# Negative control of a spec's certification: SPEC with the first decimal of every method's
# first kick weight moved by one must fail erkn-generate (GENERATE) at a named tree.
file(READ ${SPEC} text)
if(NOT text MATCHES "\nkick +-?[0-9]*\\.([0-9])")
  message(FATAL_ERROR "no kick line in ${SPEC}")
endif()
math(EXPR moved "(${CMAKE_MATCH_1} + 1) % 10")
string(REGEX REPLACE "(\nkick +-?[0-9]*\\.)${CMAKE_MATCH_1}" "\\1${moved}" wrong "${text}")
file(WRITE ${WORK}/wrong.spec "${wrong}")
execute_process(COMMAND ${GENERATE} ${WORK}/wrong.spec --out ${WORK}/out RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT "${out}${err}" MATCHES "fails at tree")
  message(FATAL_ERROR "a moved digit was certified (exit ${rc}):\n${out}${err}")
endif()
