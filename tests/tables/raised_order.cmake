# Negative control of the order certification: for every method of SPEC, a spec holding that
# method alone with its claimed order raised by one must be refused by erkn-generate with a
# message naming the method and the first failing tree. Decimal explicit methods are polished onto
# the orders their digits meet, and the refusal says that they do not meet the claim.
file(READ ${SPEC} text)
string(REPLACE ";" "<semicolon>" text "${text}")  # `diagonal` lists: not CMake list separators
string(REGEX MATCHALL "\nmethod[ \t]+[^\n]*\n([^m\n][^\n]*\n|modified[^\n]*\n)*" blocks "\n${text}")
list(LENGTH blocks n)
if(n EQUAL 0)
  message(FATAL_ERROR "no method blocks found in ${SPEC}")
endif()
foreach(block IN LISTS blocks)
  string(REGEX MATCH "method[ \t]+([^\n]*)" _ "${block}")
  set(name "${CMAKE_MATCH_1}")
  string(REGEX MATCH "\norder[ \t]+([0-9]+)" _ "${block}")
  math(EXPR raised "${CMAKE_MATCH_1} + 1")
  string(REGEX REPLACE "\norder[ \t]+[0-9]+" "\norder ${raised}" raised_block "${block}")
  string(REPLACE "<semicolon>" ";" raised_block "${raised_block}")
  file(WRITE ${WORKDIR}/raised.spec "${raised_block}")
  file(MAKE_DIRECTORY ${WORKDIR}/out/include/erkn/generated ${WORKDIR}/out/src)
  execute_process(COMMAND ${GENERATOR} ${WORKDIR}/raised.spec ${WORKDIR}/out
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  string(REGEX REPLACE "([][()+.*^$?|\\\\])" "\\\\\\1" name_re "${name}")
  if(rc EQUAL 0 OR NOT err MATCHES "${name_re}: claimed order ${raised} fails at tree f")
    message(FATAL_ERROR "${name} with order ${raised}: expected a refusal naming it and a tree, "
                        "got exit ${rc}: ${err}")
  endif()
  if(block MATCHES "\nkind[ \t]+explicit" AND block MATCHES "\n(c|d|drift|kick)[ \t]+[^\n]*[0-9]\\.[0-9]"
     AND NOT err MATCHES "the decimals do not meet the claim \\(polished onto the orders they meet")
    message(FATAL_ERROR "${name} with order ${raised}: the refusal does not say that the decimals "
                        "do not meet the claim: ${err}")
  endif()
  message(STATUS "refused as expected: ${err}")
endforeach()
