# Negative control of the order certification: for every method of SPEC, a spec holding that
# method alone with its claimed order raised by one must be refused by erkn-generate with a
# message naming the method and the first failing tree. Decimal explicit methods are polished onto
# the orders their digits meet, and the refusal says that they do not meet the claim.
include(${CMAKE_CURRENT_LIST_DIR}/refusal.cmake)
spec_blocks(${SPEC} blocks)
foreach(block IN LISTS blocks)
  block_name("${block}" name)
  string(REGEX MATCH "\norder[ \t]+([0-9]+)" _ "${block}")
  math(EXPR raised "${CMAKE_MATCH_1} + 1")
  string(REGEX REPLACE "\norder[ \t]+[0-9]+" "\norder ${raised}" raised_block "${block}")
  # (a processed method's claim is that of pi o K o pi^-1, which the message says)
  expect_refusal("${raised_block}" raised.spec
                 "${name_re}: claimed order ${raised}( \\(of pi o K o pi\\^-1[^)]*\\))? fails at tree f"
                 "${name} with order ${raised}" err)
  if(block MATCHES "\nkind[ \t]+explicit" AND block MATCHES "\n(c|d|drift|kick)[ \t]+[^\n]*[0-9]\\.[0-9]"
     AND NOT err MATCHES "the decimals do not meet the claim \\(polished onto the orders they meet")
    message(FATAL_ERROR "${name} with order ${raised}: the refusal does not say that the decimals "
                        "do not meet the claim: ${err}")
  endif()
endforeach()
