# Negative control: SERKN2s4 with c1 moved by 1/1000 (d_i still solved from the first two
# quadrature conditions) is order 2: b_i(V) moves with c_i, and the first condition of power 3,
# [V^1] of sum_i b_i(V) = phi1(V) at the tree f, fails (sum d_i c_i^2 = 1/3 fails at f[p,p] too).
include(${CMAKE_CURRENT_LIST_DIR}/refusal.cmake)
file(READ ${SPEC} text)
string(REGEX MATCH "method[ \t]+SERKN2s4\n([^m\n][^\n]*\n|\n)*" block "${text}")
string(REPLACE "c         (3-sqrt(3))/6," "c         (3-sqrt(3))/6+1/1000," perturbed "${block}")
if(perturbed STREQUAL block)
  message(FATAL_ERROR "SERKN2s4's nodes not found in ${SPEC}")
endif()
expect_refusal("${perturbed}" perturbed.spec
               "SERKN2s4: claimed order 4 fails at tree f: condition \\[V\\^1\\] b\\^T Phi\\(f\\).*certified order 2"
               "SERKN2s4 with c1 + 1/1000 (order 2 expected)" err)
