# A spec whose abar22 has a factor common to numerator and denominator derives (the factor is
# divided out), certifies order 4, and lists only the true poles 4 pi^2 and 16 pi^2 (zeros of
# the denominators of abar11 and abar33, see common_factor.spec); raising the order is refused.
include(${CMAKE_CURRENT_LIST_DIR}/spec_checks.cmake)
derive_spec(md)
if(NOT md MATCHES "## Quarter3s4[^#]*Real poles in \\(0, 200\\]: 39\\.47841760435[0-9]*, 157\\.9136704174[0-9]*\\.[^#]*\\*\\*order 4\\*\\*")
  message(FATAL_ERROR "Quarter3s4: expected poles 4 pi^2, 16 pi^2 and order 4:\n${md}")
endif()
expect_raised_order_refused(Quarter3s4 4)
