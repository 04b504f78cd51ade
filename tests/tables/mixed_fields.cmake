# Nodes in different quadratic fields (sqrt(2) with sqrt(3)) derive, certify order 4 in 60-digit
# arithmetic and list their poles; raising the order to 5 is refused naming the method and a tree.
execute_process(COMMAND ${GENERATOR} ${SPEC} ${WORKDIR}/ok RESULT_VARIABLE rc ERROR_VARIABLE err)
file(READ ${WORKDIR}/ok/derivation.md md)
if(NOT rc EQUAL 0 OR NOT md MATCHES "## Mixed3s4[^#]*Real poles in \\(0, 200\\]: [0-9][^#]*60-digit CLN arithmetic[^#]*\\*\\*order 4\\*\\*")
  message(FATAL_ERROR "Mixed3s4 did not derive with order 4 (exit ${rc}): ${err}")
endif()
file(READ ${SPEC} spec)
string(REPLACE "order     4" "order     5" raised "${spec}")
file(WRITE ${WORKDIR}/raised.spec "${raised}")
execute_process(COMMAND ${GENERATOR} ${WORKDIR}/raised.spec ${WORKDIR}/raised
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "Mixed3s4: claimed order 5 fails at tree f")
  message(FATAL_ERROR "expected Mixed3s4 of order 5 to be refused at a tree: ${err}")
endif()
