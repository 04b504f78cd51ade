# Runs ERKN with ARGS (a ;-list); passes if it exits 0 with EXPECT in its standard output and
# nothing on standard error (--help is an answer, not an error).
execute_process(COMMAND ${ERKN} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "expected exit 0, got ${rc}: ${out}${err}")
endif()
if(NOT out MATCHES "${EXPECT}" OR NOT err STREQUAL "")
  message(FATAL_ERROR "output '${out}' (error output '${err}') does not match '${EXPECT}'")
endif()
