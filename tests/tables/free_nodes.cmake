# Two free nodes are solved: TwoFree2s4 (c = ?, ?) has the closed forms, poles and certified
# order of TwoGiven2s4 (the same nodes written out). Refused, naming the method: two free nodes
# with too few quadrature conditions (order < s + 2), and three free nodes.
execute_process(COMMAND ${GENERATOR} ${SPEC} ${WORKDIR}/ok RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "free-node spec did not derive (exit ${rc}): ${err}")
endif()
file(READ ${WORKDIR}/ok/derivation.md md)
foreach(name TwoFree2s4 TwoGiven2s4)
  if(NOT md MATCHES "## ${name} [^#]*(Closed forms[^#]*\\*\\*order 4\\*\\*)")
    message(FATAL_ERROR "${name}: no closed forms with certified order 4:\n${md}")
  endif()
  set(${name} "${CMAKE_MATCH_1}")
endforeach()
if(NOT TwoFree2s4 STREQUAL TwoGiven2s4)
  message(FATAL_ERROR "solved nodes give another method:\n${TwoFree2s4}\n---\n${TwoGiven2s4}")
endif()

function(expect_refusal label text pattern)
  file(WRITE ${WORKDIR}/${label}.spec "${text}")
  execute_process(COMMAND ${GENERATOR} ${WORKDIR}/${label}.spec ${WORKDIR}/${label}
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "${label}: expected a refusal matching '${pattern}', got: ${err}")
  endif()
endfunction()
set(head "method Few\nrkn RKNFew\nsource test\nstages 3\norder 4\n")
set(diag "diagonal bbarAe == phi(4, v); bAe == phi(3, v); bcAe == 3*phi(4, v)\n")
expect_refusal(too_few "${head}c 1/2, ?, ?\n${diag}"
               "Few: 2 free nodes need the quadrature conditions k = 3, 4 .* order >= 5")
expect_refusal(three "${head}c ?, ?, ?\n${diag}" "Few: 3 free nodes: the generator solves at most two")
