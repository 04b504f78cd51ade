# Helpers of the generator's spec tests (cmake -P scripts given GENERATOR, SPEC and WORKDIR).

# derive_spec(OUT_MD): the generator on SPEC into WORKDIR/ok must succeed; OUT_MD receives the
# text of its derivation.md.
function(derive_spec out_md)
  execute_process(COMMAND ${GENERATOR} ${SPEC} ${WORKDIR}/ok RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "erkn-generate failed on ${SPEC} (exit ${rc}): ${err}")
  endif()
  file(READ ${WORKDIR}/ok/derivation.md md)
  set(${out_md} "${md}" PARENT_SCOPE)
endfunction()

# expect_raised_order_refused(NAME FROM [DETAIL]): SPEC with its "order FROM" lines raised by one
# is refused, the error naming NAME, the claimed order and a failing tree (then matching DETAIL).
function(expect_raised_order_refused name from)
  math(EXPR to "${from} + 1")
  file(READ ${SPEC} spec)
  string(REGEX REPLACE "order     ${from}\n" "order     ${to}\n" raised "${spec}")
  file(WRITE ${WORKDIR}/raised.spec "${raised}")
  execute_process(COMMAND ${GENERATOR} ${WORKDIR}/raised.spec ${WORKDIR}/raised
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "${name}: claimed order ${to} fails at tree f${ARGN}")
    message(FATAL_ERROR "expected ${name} of order ${to} to be refused at a tree: ${err}")
  endif()
  message(STATUS "refused as expected: ${err}")
endfunction()
