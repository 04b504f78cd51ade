# Runs ERKN with ARGS (a ;-list); passes if it exits non-zero with EXPECT in its error output.
execute_process(COMMAND ${ERKN} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "expected a refusal, got exit 0 and: ${out}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "error message '${err}' does not match '${EXPECT}'")
endif()
message(STATUS "refused as expected: ${err}")
