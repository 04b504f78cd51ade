# Nodes in different quadratic fields (sqrt(2) with sqrt(3)) derive, certify order 4 in 60-digit
# arithmetic and list their poles; raising the order to 5 is refused naming the method and a tree.
include(${CMAKE_CURRENT_LIST_DIR}/spec_checks.cmake)
derive_spec(md)
if(NOT md MATCHES "## Mixed3s4[^#]*Real poles in \\(0, 200\\]: [0-9][^#]*60-digit CLN arithmetic[^#]*\\*\\*order 4\\*\\*")
  message(FATAL_ERROR "Mixed3s4 did not derive with order 4:\n${md}")
endif()
expect_raised_order_refused(Mixed3s4 4)
