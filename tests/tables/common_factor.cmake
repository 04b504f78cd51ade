# A spec whose abar22 has a factor common to numerator and denominator derives (the factor is
# divided out), certifies order 4, and lists only the true poles 4 pi^2 and 16 pi^2 (zeros of
# the denominators of abar11 and abar33, see common_factor.spec); raising the order is refused.
execute_process(COMMAND ${GENERATOR} ${SPEC} ${WORKDIR}/ok RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "Quarter3s4 did not derive (exit ${rc}): ${err}")
endif()
file(READ ${WORKDIR}/ok/derivation.md md)
if(NOT md MATCHES "## Quarter3s4[^#]*Real poles in \\(0, 200\\]: 39\\.47841760435[0-9]*, 157\\.9136704174[0-9]*\\.[^#]*\\*\\*order 4\\*\\*")
  message(FATAL_ERROR "Quarter3s4: expected poles 4 pi^2, 16 pi^2 and order 4:\n${md}")
endif()
file(READ ${SPEC} spec)
string(REPLACE "order     4" "order     5" raised "${spec}")
file(WRITE ${WORKDIR}/raised.spec "${raised}")
execute_process(COMMAND ${GENERATOR} ${WORKDIR}/raised.spec ${WORKDIR}/raised
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "Quarter3s4: claimed order 5 fails at tree f")
  message(FATAL_ERROR "expected Quarter3s4 of order 5 to be refused at a tree: ${err}")
endif()
